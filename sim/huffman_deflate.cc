#include "sim/huffman_deflate.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <queue>
#include <stdexcept>
#include <utility>

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "BitWriter stores its 64-bit accumulator as bytes: it needs a little-endian machine"
#endif

namespace viqu::sim {
namespace {

// Input bytes per deflate block: each gets its own code (large enough that the ~100-byte block
// header is lost in it, small enough to follow a change of content down an image).
constexpr size_t kBlockBytes = 128 * 1024;
constexpr int kEndOfBlock = 256;
constexpr int kLiteralSymbols = 257;   // 0-255 and end of block (no length codes are used)
constexpr int kMaxCodeBits = 15;       // RFC 1951 3.2.7
constexpr int kMaxCodeLengthBits = 7;  // the code-length code's limit (3-bit fields)
// The order in which the code-length code's lengths are sent (RFC 1951 3.2.7).
constexpr int kCodeLengthOrder[19] = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};

// Least significant bit first, as deflate packs its bits, into a buffer sized beforehand: each
// flush stores 8 bytes at once and advances by the whole bytes written, so the buffer needs
// 8 bytes of slack past the last byte it keeps (Reserve).
class BitWriter {
 public:
  explicit BitWriter(std::vector<uint8_t>* out) : out_(out), pos_(out->size()) {}
  // Makes room for `bits` more bits.
  void Reserve(size_t bits) {
    const size_t need = pos_ + bits / 8 + 16;
    if (out_->size() < need) out_->resize(std::max(need, out_->size() * 3 / 2));
  }
  // At most 63 bits may be pending at a Flush (after one, at most 7 are).
  void Put(uint64_t bits, int count) {
    acc_ |= bits << used_;
    used_ += count;
  }
  void Flush() {
    std::memcpy(out_->data() + pos_, &acc_, 8);  // little-endian: LSB first, as deflate wants
    pos_ += static_cast<size_t>(used_ >> 3);
    acc_ >>= (used_ & ~7);
    used_ &= 7;
  }
  int pending() const { return used_; }
  void PutFlushed(uint64_t bits, int count) {
    Put(bits, count);
    Flush();
  }
  // Pads the last byte with zeros and trims the buffer to the bytes written.
  void Finish() {
    Flush();
    if (used_ > 0) out_->data()[pos_++] = static_cast<uint8_t>(acc_);
    out_->resize(pos_);
  }

 private:
  std::vector<uint8_t>* out_;
  size_t pos_;
  uint64_t acc_ = 0;
  int used_ = 0;
};

// Depths of the leaves of a Huffman tree over the nonzero frequencies (ties broken by node order,
// so the result is deterministic).
std::vector<int> HuffmanDepths(const std::vector<uint64_t>& weight) {
  const int n = static_cast<int>(weight.size());
  std::vector<int> parent(2 * n, -1);
  using Node = std::pair<uint64_t, int>;  // weight, node index
  std::priority_queue<Node, std::vector<Node>, std::greater<Node>> heap;
  for (int i = 0; i < n; ++i) {
    if (weight[i] > 0) heap.push({weight[i], i});
  }
  int next = n;
  while (heap.size() > 1) {
    const Node a = heap.top();
    heap.pop();
    const Node b = heap.top();
    heap.pop();
    parent[a.second] = parent[b.second] = next;
    heap.push({a.first + b.first, next++});
  }
  std::vector<int> depth(n, 0);
  for (int i = 0; i < n; ++i) {
    if (weight[i] == 0) continue;
    for (int p = parent[i]; p != -1; p = parent[p]) ++depth[i];
  }
  return depth;
}

// Canonical codes for the lengths (RFC 1951 3.2.2), bit-reversed for LSB-first output.
std::vector<uint32_t> CanonicalCodes(const std::vector<uint8_t>& lengths) {
  int count[kMaxCodeBits + 1] = {};
  for (uint8_t l : lengths) ++count[l];
  count[0] = 0;
  uint32_t next[kMaxCodeBits + 2] = {};
  uint32_t code = 0;
  for (int bits = 1; bits <= kMaxCodeBits; ++bits) {
    code = (code + count[bits - 1]) << 1;
    next[bits] = code;
  }
  std::vector<uint32_t> codes(lengths.size(), 0);
  for (size_t s = 0; s < lengths.size(); ++s) {
    const int len = lengths[s];
    if (len == 0) continue;
    const uint32_t c = next[len]++;
    uint32_t reversed = 0;
    for (int b = 0; b < len; ++b) reversed |= ((c >> b) & 1u) << (len - 1 - b);
    codes[s] = reversed;
  }
  return codes;
}

// Writes a dynamic-Huffman block header (RFC 1951 3.2.7) for the given literal/length and
// distance code lengths, each code length sent by the code-length code (no repeat codes).
void PutHeader(const std::vector<uint8_t>& lit_len, const std::vector<uint8_t>& dist_len, bool final, BitWriter* w) {
  std::vector<uint8_t> sent(lit_len);
  sent.insert(sent.end(), dist_len.begin(), dist_len.end());
  std::vector<uint32_t> cl_freq(19, 0);
  for (uint8_t l : sent) ++cl_freq[l];
  const std::vector<uint8_t> cl_len = LimitedCodeLengths(cl_freq, kMaxCodeLengthBits);
  const std::vector<uint32_t> cl_code = CanonicalCodes(cl_len);
  w->Reserve(17 + 19 * 3 + sent.size() * kMaxCodeLengthBits);
  w->PutFlushed(final ? 1 : 0, 1);
  w->PutFlushed(2, 2);                                       // dynamic Huffman codes
  w->PutFlushed(lit_len.size() - 257, 5);                    // HLIT
  w->PutFlushed(dist_len.size() - 1, 5);                     // HDIST
  w->PutFlushed(19 - 4, 4);                                  // HCLEN: all 19 code-length code lengths
  for (int s : kCodeLengthOrder) w->PutFlushed(cl_len[s], 3);
  for (uint8_t l : sent) w->PutFlushed(cl_code[l], cl_len[l]);
}

void PutBlock(const uint8_t* data, size_t n, bool final, BitWriter* w) {
  // Four partial histograms: consecutive equal bytes would otherwise wait on each other's count.
  uint32_t part[4][256] = {};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    ++part[0][data[i]];
    ++part[1][data[i + 1]];
    ++part[2][data[i + 2]];
    ++part[3][data[i + 3]];
  }
  for (; i < n; ++i) ++part[0][data[i]];
  std::vector<uint32_t> freq(kLiteralSymbols, 0);
  for (int s = 0; s < 256; ++s) freq[s] = part[0][s] + part[1][s] + part[2][s] + part[3][s];
  freq[kEndOfBlock] = 1;
  const std::vector<uint8_t> lit_len = LimitedCodeLengths(freq, kMaxCodeBits);
  const std::vector<uint32_t> lit_code = CanonicalCodes(lit_len);

  // One distance code of length 1: no distance is ever used; RFC 1951 asks for one code of one
  // bit then.
  PutHeader(lit_len, {1}, final, w);
  uint64_t bits = 0;
  for (size_t s = 0; s < kLiteralSymbols; ++s) bits += static_cast<uint64_t>(freq[s]) * lit_len[s];
  w->Reserve(bits + kMaxCodeBits);
  // Code and length of each byte in one word (code in the low 16 bits); three codes of at most
  // 15 bits and the 7 left over from the last flush fit the accumulator.
  uint32_t table[256];
  for (int s = 0; s < 256; ++s) table[s] = lit_code[s] | (static_cast<uint32_t>(lit_len[s]) << 16);
  i = 0;
  for (; i + 3 <= n; i += 3) {
    const uint32_t a = table[data[i]], b = table[data[i + 1]], c = table[data[i + 2]];
    w->Put(a & 0xffff, static_cast<int>(a >> 16));
    w->Put(b & 0xffff, static_cast<int>(b >> 16));
    w->Put(c & 0xffff, static_cast<int>(c >> 16));
    w->Flush();
  }
  for (; i < n; ++i) w->PutFlushed(table[data[i]] & 0xffff, static_cast<int>(table[data[i]] >> 16));
  w->PutFlushed(lit_code[kEndOfBlock], lit_len[kEndOfBlock]);
}

// --- Repeats at fixed distances ---------------------------------------------------------------
// Deflate's length and distance symbols (RFC 1951 3.2.5): lengths 3-258 as symbols 257-285 with
// extra bits, distances 1-32768 as codes 0-29 with extra bits.
constexpr int kLengthSymbols = 286;  // literals, end of block, lengths
constexpr int kDistanceSymbols = 30;
constexpr int kMinMatch = 3, kMaxMatch = 258, kMaxDistance = 32768;
constexpr int kLengthBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr int kLengthExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr int kDistanceBase[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
                                   193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr int kDistanceExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

// Symbol, extra-bit count and extra value of a length or a distance.
struct SymbolWithExtra {
  int symbol = 0, extra_bits = 0;
  uint32_t extra = 0;
};
SymbolWithExtra OfLength(int length) {
  int c = 28;
  while (kLengthBase[c] > length) --c;
  return {257 + c, kLengthExtra[c], static_cast<uint32_t>(length - kLengthBase[c])};
}
SymbolWithExtra OfDistance(int distance) {
  int c = 29;
  while (kDistanceBase[c] > distance) --c;
  return {c, kDistanceExtra[c], static_cast<uint32_t>(distance - kDistanceBase[c])};
}

// OfLength for every length, computed once.
const std::vector<SymbolWithExtra>& LengthTable() {
  static const std::vector<SymbolWithExtra> table = [] {
    std::vector<SymbolWithExtra> t(kMaxMatch + 1);
    for (int len = kMinMatch; len <= kMaxMatch; ++len) t[len] = OfLength(len);
    return t;
  }();
  return table;
}

// How many bytes from `a` equal those from `b` (at most `limit`), eight at a time.
inline size_t MatchLength(const uint8_t* a, const uint8_t* b, size_t limit) {
  size_t k = 0;
  while (k + 8 <= limit) {
    uint64_t x, y;
    std::memcpy(&x, a + k, 8);
    std::memcpy(&y, b + k, 8);
    if (x != y) return k + static_cast<size_t>(__builtin_ctzll(x ^ y) >> 3);  // little-endian
    k += 8;
  }
  while (k < limit && a[k] == b[k]) ++k;
  return k;
}

// One block of literals and repeats: the tokens are found first (greedy, the longest repeat at
// the candidate distances, the first candidate on a tie), then coded with this block's codes.
void PutRepeatBlock(const uint8_t* data, size_t begin, size_t end, bool final, const std::vector<int>& distances,
                    std::vector<uint32_t>* tokens, BitWriter* w) {
  std::vector<uint32_t> lit_freq(kLengthSymbols, 0), dist_freq(kDistanceSymbols, 0);
  std::vector<SymbolWithExtra> dist_sym;
  for (int d : distances) dist_sym.push_back(OfDistance(d));
  const SymbolWithExtra* length_sym = LengthTable().data();
  // A token: a byte (< 256), or 0x80000000 | candidate << 16 | length.
  tokens->clear();
  size_t i = begin;
  while (i < end) {
    const size_t limit = std::min<size_t>(kMaxMatch, end - i);
    size_t best = 0, best_c = 0;
    if (limit >= kMinMatch) {
      for (size_t c = 0; c < distances.size(); ++c) {
        const size_t d = static_cast<size_t>(distances[c]);
        if (d > i) continue;  // the window holds what came before, in earlier blocks too
        const size_t len = MatchLength(data + i, data + i - d, limit);
        if (len > best) {
          best = len;
          best_c = c;
        }
      }
    }
    if (best >= kMinMatch) {
      tokens->push_back(0x80000000u | static_cast<uint32_t>(best_c << 16) | static_cast<uint32_t>(best));
      ++lit_freq[length_sym[best].symbol];
      ++dist_freq[dist_sym[best_c].symbol];
      i += best;
    } else {
      tokens->push_back(data[i]);
      ++lit_freq[data[i]];
      ++i;
    }
  }
  lit_freq[kEndOfBlock] = 1;
  const std::vector<uint8_t> lit_len = LimitedCodeLengths(lit_freq, kMaxCodeBits);
  const std::vector<uint32_t> lit_code = CanonicalCodes(lit_len);
  const std::vector<uint8_t> dist_len = LimitedCodeLengths(dist_freq, kMaxCodeBits);
  const std::vector<uint32_t> dist_code = CanonicalCodes(dist_len);
  PutHeader(lit_len, dist_len, final, w);

  // Per length: its symbol's code and length, then its extra bits, as one put of at most
  // 15 + 5 bits; per candidate distance the same, at most 15 + 13 bits.
  struct Coded {
    uint32_t bits;
    int count;
  };
  std::vector<Coded> length_coded(kMaxMatch + 1), dist_coded(distances.size());
  for (int len = kMinMatch; len <= kMaxMatch; ++len) {
    const SymbolWithExtra& s = length_sym[len];
    length_coded[len] = {lit_code[s.symbol] | (s.extra << lit_len[s.symbol]), lit_len[s.symbol] + s.extra_bits};
  }
  for (size_t c = 0; c < distances.size(); ++c) {
    const SymbolWithExtra& s = dist_sym[c];
    dist_coded[c] = {dist_code[s.symbol] | (s.extra << dist_len[s.symbol]), dist_len[s.symbol] + s.extra_bits};
  }
  w->Reserve(tokens->size() * 48 + kMaxCodeBits);
  for (const uint32_t t : *tokens) {
    // At most 15 bits pending before a token: a literal (15 bits) or a repeat (20 + 28 bits)
    // fits the accumulator.
    if (t < 256) {
      w->Put(lit_code[t], lit_len[t]);
    } else {
      const Coded& l = length_coded[t & 0xffff];
      const Coded& d = dist_coded[(t >> 16) & 0x7fff];
      w->Put(l.bits, l.count);
      w->Put(d.bits, d.count);
    }
    if (w->pending() > 15) w->Flush();
  }
  w->PutFlushed(lit_code[kEndOfBlock], lit_len[kEndOfBlock]);
}

void PutZlibHeader(std::vector<uint8_t>* out) {
  out->resize(2);  // the capacity stays: resize within it does not reallocate
  (*out)[0] = 0x78;  // CMF: deflate, 32 KiB window
  (*out)[1] = 0x01;  // FLG: fastest compression, no dictionary; (CMF * 256 + FLG) % 31 == 0
}

void PutAdler(const uint8_t* data, size_t n, std::vector<uint8_t>* out) {
  const uLong adler = adler32(adler32(0, nullptr, 0), data, static_cast<uInt>(n));
  for (int i = 3; i >= 0; --i) out->push_back(static_cast<uint8_t>(adler >> (8 * i)));
}

}  // namespace

std::vector<uint8_t> LimitedCodeLengths(const std::vector<uint32_t>& freq, int max_bits) {
  std::vector<uint64_t> weight(freq.begin(), freq.end());
  // A code needs two symbols: give a lone one (or none) partners, the lowest unused indices.
  auto used = std::count_if(weight.begin(), weight.end(), [](uint64_t f) { return f > 0; });
  for (size_t s = 0; s < weight.size() && used < 2; ++s) {
    if (weight[s] == 0) {
      weight[s] = 1;
      ++used;
    }
  }
  while (true) {
    const std::vector<int> depth = HuffmanDepths(weight);
    if (*std::max_element(depth.begin(), depth.end()) <= max_bits) return std::vector<uint8_t>(depth.begin(), depth.end());
    // Too deep: flatten the distribution (halve every weight, keeping the used ones used) and
    // build again. Each round halves the ratio between the largest and smallest weight.
    for (uint64_t& f : weight) {
      if (f > 0) f = std::max<uint64_t>(1, f / 2);
    }
  }
}

void HuffmanOnlyZlib(const uint8_t* data, size_t n, std::vector<uint8_t>* out) {
  PutZlibHeader(out);
  BitWriter w(out);
  size_t pos = 0;
  do {
    const size_t len = std::min(kBlockBytes, n - pos);
    PutBlock(data + pos, len, pos + len == n, &w);
    pos += len;
  } while (pos < n);
  w.Finish();
  PutAdler(data, n, out);
}

void RepeatZlib(const uint8_t* data, size_t n, const std::vector<int>& distances, std::vector<uint8_t>* out) {
  if (distances.empty() || distances.size() > 0x7fff) throw std::invalid_argument("RepeatZlib: 1 to 32767 distances");
  for (int d : distances) {
    if (d < 1 || d > kMaxDistance) throw std::invalid_argument("RepeatZlib: distances must be in [1, 32768]");
  }
  PutZlibHeader(out);
  BitWriter w(out);
  std::vector<uint32_t> tokens;
  size_t pos = 0;
  do {
    const size_t len = std::min(kBlockBytes, n - pos);
    PutRepeatBlock(data, pos, pos + len, pos + len == n, distances, &tokens, &w);
    pos += len;
  } while (pos < n);
  w.Finish();
  PutAdler(data, n, out);
}

}  // namespace viqu::sim
