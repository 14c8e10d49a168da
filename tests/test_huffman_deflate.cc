// The literal-only deflate coder of the recordings, decoded by zlib's own inflater.
#include <numeric>
#include <random>

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

}  // namespace
}  // namespace viqu::sim
