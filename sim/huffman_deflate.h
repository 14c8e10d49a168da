#pragma once
// A zlib stream (RFC 1950 around RFC 1951 deflate) that codes every byte as a literal with a
// Huffman code made for each block: no string matching. For sensor images after a PNG row filter
// (noise leaves few repeated strings) it gives zlib's Z_HUFFMAN_ONLY size in about a quarter of
// its time (bench_recording: a whole 640x480 RGB PNG in 1.8 ms; zlib's mode alone took 7.8 ms).
// Any inflater reads it.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace viqu::sim {

// Replaces `*out` with the stream (its capacity is kept, so a caller that reuses one vector
// allocates, and page-faults, only for its first images).
void HuffmanOnlyZlib(const uint8_t* data, size_t n, std::vector<uint8_t>* out);

// Code lengths of a Huffman code for `freq` (one entry per symbol), none longer than `max_bits`:
// 0 for a symbol of frequency 0, except that a code always has at least two symbols (a lone
// symbol gets a partner, the lowest other index). Exposed for tests.
std::vector<uint8_t> LimitedCodeLengths(const std::vector<uint32_t>& freq, int max_bits);

}  // namespace viqu::sim
