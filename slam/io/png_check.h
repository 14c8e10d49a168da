#pragma once
// A structural check of PNG bytes before they reach the decoder: libpng prints its own errors
// ("libpng error: Read Error") to stderr before the caller can say which file is broken, so a
// truncated or damaged file is caught here and reported by the reader alone.
#include <string>

namespace viqu::io {

// True when `bytes` start with the PNG signature.
bool LooksLikePng(const std::string& bytes);

// Why `bytes` are no intact PNG (signature, chunk lengths within the file, every chunk's CRC,
// IHDR first, IEND last and nothing after it), or "" when they are.
std::string PngStructureProblem(const std::string& bytes);

}  // namespace viqu::io
