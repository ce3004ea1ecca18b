#pragma once
// The benchmarks' main: takes the program's own option `--NAME VALUE` out of the command line,
// loads its input, then runs the registered benchmarks (Google Benchmark's options pass through).

#include "core/errors.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace mg::bench {

/// @param option  e.g. "--atoms"; its value ("" when absent) goes to `load`, which may throw
///                mg::Error (printed as one line, exit 2)
template <class Load>
int run_benchmarks(int argc, char** argv, const char* program, const char* option, Load&& load) {
  std::string value;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], option) == 0 && i + 1 < argc)
      value = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  try {
    load(value);
  } catch (const mg::Error& e) {
    std::cerr << program << ": " << e.what() << '\n';
    return 2;
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  if (benchmark::ReportUnrecognizedArguments(n, rest.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}

}  // namespace mg::bench
