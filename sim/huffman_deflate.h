#pragma once
// Zlib streams (RFC 1950 around RFC 1951 deflate) made without general string matching.
// HuffmanOnlyZlib codes every byte as a literal with a Huffman code made for each block. For
// sensor images after a PNG row filter (noise leaves few repeated strings) it gives zlib's
// Z_HUFFMAN_ONLY size in about a quarter of its time (bench_recording: a whole 640x480 RGB PNG in 1.8 ms; zlib's mode alone took 7.8 ms).
// Any inflater reads it.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace viqu::sim {

// Replaces `*out` with the stream (its capacity is kept, so a caller that reuses one vector
// allocates, and page-faults, only for its first images).
void HuffmanOnlyZlib(const uint8_t* data, size_t n, std::vector<uint8_t>* out);

// Literals and repeats found only at the given distances back (for a filtered image: 1 for runs
// of one byte, the pixel size, the row length), the longest at each position taken greedily,
// with codes made for each block. For label images, whose repeats sit at these few distances,
// it takes half the time of zlib's string matching at level 1 and gives smaller files; for depth
// four fifths of the time at larger files (PngEncoder's comment has the figures). Distances must be in [1, 32768]; throws std::invalid_argument else.
void RepeatZlib(const uint8_t* data, size_t n, const std::vector<int>& distances, std::vector<uint8_t>* out);

// Code lengths of a Huffman code for `freq` (one entry per symbol), none longer than `max_bits`:
// 0 for a symbol of frequency 0, except that a code always has at least two symbols (a lone
// symbol gets a partner, the lowest other index). Exposed for tests.
std::vector<uint8_t> LimitedCodeLengths(const std::vector<uint32_t>& freq, int max_bits);

}  // namespace viqu::sim
