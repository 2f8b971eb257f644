#pragma once
// Summary statistics of a set of timings (benchmarks, latency reports). Header-only: stratad, the
// client and the benchmarks all use it.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace strata::util {

struct Summary {
  double mean = 0.0;
  double p50 = 0.0;  // the element at index n/2 of the sorted values
  double p95 = 0.0;
  double max = 0.0;
};

inline Summary summarize(std::vector<double> v) {
  Summary s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  for (double x : v) s.mean += x;
  s.mean /= double(v.size());
  s.p50 = v[v.size() / 2];
  s.p95 = v[std::min(v.size() - 1, size_t(double(v.size()) * 0.95))];
  s.max = v.back();
  return s;
}

}  // namespace strata::util
