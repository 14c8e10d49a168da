#pragma once
// Strict parsing of the numbers in dataset tables: the whole field must be the number.
#include <cstdint>
#include <string>

namespace viqu::io {

// An integer such as EuRoC's nanosecond stamps "1403636579763555584". False on anything else,
// including overflow.
bool ParseInt64(const std::string& text, int64_t* out);

// Seconds as TUM writes them ("1305031102.175304") to nanoseconds, exactly for up to 9
// decimals (more are rounded to the nearest nanosecond). False on anything else or overflow.
bool ParseSecondsAsNs(const std::string& text, int64_t* out_ns);

// A finite floating-point number. False on anything else (also "nan", "inf").
bool ParseFiniteDouble(const std::string& text, double* out);

}  // namespace viqu::io
