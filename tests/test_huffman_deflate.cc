// The deflate coders of the recordings (literal-only, and literals with repeats at fixed
// distances), decoded by zlib's own inflater.
#include <cstdio>
#include <numeric>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <zlib.h>

#include "sim/huffman_deflate.h"

namespace viqu::sim {
namespace {

std::vector<uint8_t> Inflate(const std::vector<uint8_t>& z, size_t expected_size) {
  std::vector<uint8_t> out(expected_size + 16);
  uLongf len = out.size();
  const int rc = uncompress(out.data(), &len, z.data(), z.size());
  EXPECT_EQ(rc, Z_OK);
  out.resize(rc == Z_OK ? len : 0);
  return out;
}

std::vector<uint8_t> Deflate(const std::vector<uint8_t>& data) {
  std::vector<uint8_t> z = {1, 2, 3};  // whatever the vector held before is replaced
  HuffmanOnlyZlib(data.data(), data.size(), &z);
  return z;
}

void ExpectRoundTrip(const std::vector<uint8_t>& data) { EXPECT_EQ(Inflate(Deflate(data), data.size()), data); }

TEST(HuffmanDeflate, RandomBytesOfEveryValue) {
  std::mt19937 rng(7);
  std::vector<uint8_t> data(100000);
  for (uint8_t& b : data) b = static_cast<uint8_t>(rng());
  ExpectRoundTrip(data);
}

TEST(HuffmanDeflate, SkewedBytesCompressLikeZlibsHuffmanOnlyMode) {
  // Sensor-like residuals: small differences around zero, as a PNG Sub filter leaves them.
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 3.0);
  std::vector<uint8_t> data(600000);  // several blocks
  for (uint8_t& b : data) b = static_cast<uint8_t>(static_cast<int>(std::lround(noise(rng))) & 0xff);
  const std::vector<uint8_t> ours = Deflate(data);
  EXPECT_EQ(Inflate(ours, data.size()), data);
  z_stream s{};
  ASSERT_EQ(deflateInit2(&s, 1, Z_DEFLATED, 15, 8, Z_HUFFMAN_ONLY), Z_OK);
  std::vector<uint8_t> theirs(deflateBound(&s, data.size()));
  s.next_in = data.data();
  s.avail_in = static_cast<uInt>(data.size());
  s.next_out = theirs.data();
  s.avail_out = static_cast<uInt>(theirs.size());
  ASSERT_EQ(deflate(&s, Z_FINISH), Z_STREAM_END);
  const double zlib_size = s.total_out;
  deflateEnd(&s);
  EXPECT_LT(ours.size(), 1.02 * zlib_size);
  EXPECT_LT(ours.size(), data.size() / 2) << "an entropy of about 3.5 bits a byte";
}

TEST(HuffmanDeflate, EmptyAndSingleValueInputs) {
  ExpectRoundTrip({});
  ExpectRoundTrip({42});
  ExpectRoundTrip(std::vector<uint8_t>(300000, 0));  // one literal across blocks: a two-symbol code
}

TEST(HuffmanDeflate, CodeLengthsStayWithinTheLimit) {
  // Fibonacci frequencies make the deepest plain Huffman tree: 25 symbols, depth 24.
  std::vector<uint32_t> freq(257, 0);
  uint32_t a = 1, b = 1;
  for (int s = 0; s < 25; ++s) {
    freq[s] = a;
    const uint32_t c = a + b;
    a = b;
    b = c;
  }
  const std::vector<uint8_t> len = LimitedCodeLengths(freq, 15);
  double kraft = 0;
  for (int s = 0; s < 257; ++s) {
    EXPECT_LE(len[s], 15);
    EXPECT_EQ(len[s] > 0, freq[s] > 0) << s;
    if (len[s]) kraft += std::ldexp(1.0, -len[s]);
  }
  EXPECT_DOUBLE_EQ(kraft, 1.0) << "a complete code";
  // And the bytes themselves survive the coder.
  std::vector<uint8_t> data;
  for (int s = 0; s < 25; ++s) data.insert(data.end(), std::min<uint32_t>(freq[s], 20000), static_cast<uint8_t>(s));
  ExpectRoundTrip(data);
}

TEST(HuffmanDeflate, ALoneSymbolGetsAPartner) {
  std::vector<uint32_t> freq(19, 0);
  freq[8] = 258;
  const std::vector<uint8_t> len = LimitedCodeLengths(freq, 7);
  EXPECT_EQ(len[8], 1);
  EXPECT_EQ(len[0], 1);
  EXPECT_EQ(std::accumulate(len.begin(), len.end(), 0), 2);
}

std::vector<uint8_t> DeflateRepeats(const std::vector<uint8_t>& data, const std::vector<int>& distances) {
  std::vector<uint8_t> z = {9, 9};
  RepeatZlib(data.data(), data.size(), distances, &z);
  return z;
}

void ExpectRepeatRoundTrip(const std::vector<uint8_t>& data, const std::vector<int>& distances) {
  EXPECT_EQ(Inflate(DeflateRepeats(data, distances), data.size()), data);
}

TEST(RepeatDeflate, RoundTripsEveryKindOfInput) {
  std::mt19937 rng(5);
  std::vector<uint8_t> random(200000);
  for (uint8_t& b : random) b = static_cast<uint8_t>(rng());
  ExpectRepeatRoundTrip(random, {1, 2, 1281});
  ExpectRepeatRoundTrip({}, {1});
  ExpectRepeatRoundTrip({7}, {1});
  ExpectRepeatRoundTrip({7, 7}, {1});
  ExpectRepeatRoundTrip({7, 7, 7, 7, 7}, {1});                              // a run shorter than a repeat's minimum + 1
  ExpectRepeatRoundTrip(std::vector<uint8_t>(300000, 0), {1});              // runs longer than 258, across blocks
  ExpectRepeatRoundTrip(std::vector<uint8_t>(1000, 3), {32768, 1});         // a distance longer than the input
  // Every length from 3 to 258 (each symbol and extra-bit value) at every kind of distance.
  std::vector<uint8_t> lengths;
  for (int len = 1; len <= 260; ++len) {
    lengths.push_back(static_cast<uint8_t>(rng()));
    lengths.insert(lengths.end(), len, lengths.back());
  }
  ExpectRepeatRoundTrip(lengths, {1});
  ExpectRepeatRoundTrip(lengths, {2, 5, 1, 300, 32768});
}

// Images after a PNG row filter repeat at the row length (edges of labels) and at the pixel size
// (16-bit values): found there, they compress far below the literal coder, and the stream still
// decodes when a repeat reaches into the block before.
TEST(RepeatDeflate, FindsRepeatsOfRowsAndPixels) {
  const size_t row = 1281, rows = 400;  // a 640-pixel 16-bit image's filtered rows
  std::mt19937 rng(9);
  std::vector<uint8_t> line(row);
  for (uint8_t& b : line) b = static_cast<uint8_t>(rng() % 4);
  std::vector<uint8_t> image;
  for (size_t r = 0; r < rows; ++r) {
    if (r % 50 == 0) line[rng() % row] ^= 1;  // now and then a row changes
    image.insert(image.end(), line.begin(), line.end());
  }
  const std::vector<uint8_t> with_rows = DeflateRepeats(image, {1, 2, static_cast<int>(row)});
  EXPECT_EQ(Inflate(with_rows, image.size()), image);
  // Measured 41x smaller than literals (3.4 against 143 KB).
  EXPECT_LT(with_rows.size(), Deflate(image).size() / 20) << "rows repeat: a few repeats a row";
  // 16-bit samples of a slope: high byte 0, the low byte (the step to the left) changing every
  // 200 pixels. No byte repeats the one before it; each pixel repeats the one before.
  std::vector<uint8_t> pairs;
  for (int i = 0; i < 100000; ++i) pairs.insert(pairs.end(), {0, static_cast<uint8_t>(3 + (i / 200) % 3)});
  const std::vector<uint8_t> with_pixels = DeflateRepeats(pairs, {1, 2});
  EXPECT_EQ(Inflate(with_pixels, pairs.size()), pairs);
  const size_t bytes_only = DeflateRepeats(pairs, {1}).size();
  std::printf("slope: %zu bytes with pixel repeats, %zu with byte runs only\n", with_pixels.size(), bytes_only);
  EXPECT_LT(with_pixels.size(), bytes_only / 10);
}

TEST(RepeatDeflate, RejectsDistancesOutsideTheWindow) {
  const std::vector<uint8_t> data(10, 1);
  EXPECT_THROW(DeflateRepeats(data, {}), std::invalid_argument);
  EXPECT_THROW(DeflateRepeats(data, {0}), std::invalid_argument);
  EXPECT_THROW(DeflateRepeats(data, {32769}), std::invalid_argument);
}

}  // namespace
}  // namespace viqu::sim
