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
// after the stamp, or `n_alt` (when not 0; a stream that gained columns: every row holds as many
// as the first, and on_row tells the layouts apart by values.size()).
template <typename F>
void ReadStampedRows(const std::string& path, size_t n, F&& on_row, size_t n_alt = 0) {
  TextTableReader table(path, ',');
  std::vector<std::string> f;
  std::vector<double> v;
  int64_t last = 0;
  bool first = true;
  size_t count = n;  // numbers a row holds
  while (table.Next(&f)) {
    if (first && n_alt > 0 && f.size() == n_alt + 1) count = n_alt;
    if (f.size() != count + 1) {
      const std::string want = std::to_string(count + 1) +
                               (first && n_alt > 0 ? " or " + std::to_string(n_alt + 1) : std::string());
      table.Fail("expected " + want + " fields, got " + std::to_string(f.size()));
    }
    int64_t t = 0;
    if (!ParseInt64(f[0], &t)) table.Fail("timestamp '" + f[0] + "' is not an integer (ns)");
    if (!first && t <= last) table.Fail("timestamp " + f[0] + " does not follow " + std::to_string(last));
    v.resize(count);
    for (size_t i = 0; i < count; ++i) {
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
