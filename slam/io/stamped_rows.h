#pragma once
// Rows of a EuRoC-style data.csv: a stamp in ns (strictly increasing) and a fixed number of
// finite numbers. Every error names FILE:LINE (TextTableReader::Fail).
#include <cstdint>
#include <string>
#include <vector>

#include "slam/io/number_parsing.h"
#include "slam/io/text_table_reader.h"

namespace viqu::io {

// Calls on_row(t_ns, values, table) for each data row of `path`, whose rows hold `n` numbers
// after the stamp.
template <typename F>
void ReadStampedRows(const std::string& path, size_t n, F&& on_row) {
  TextTableReader table(path, ',');
  std::vector<std::string> f;
  std::vector<double> v(n);
  int64_t last = 0;
  bool first = true;
  while (table.Next(&f)) {
    if (f.size() != n + 1) {
      table.Fail("expected " + std::to_string(n + 1) + " fields, got " + std::to_string(f.size()));
    }
    int64_t t = 0;
    if (!ParseInt64(f[0], &t)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    if (!first && t <= last) table.Fail("timestamp " + f[0] + " does not follow " + std::to_string(last));
    for (size_t i = 0; i < n; ++i) {
      if (!ParseFiniteDouble(f[i + 1], &v[i])) {
        table.Fail("field " + std::to_string(i + 2) + " '" + f[i + 1] + "' is not a finite number");
      }
    }
    on_row(t, v, table);
    last = t;
    first = false;
  }
}

}  // namespace viqu::io
