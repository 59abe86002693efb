// Small POSIX helpers for rayq-validate: running the benchmark programs and gnuplot.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rayq::report {

// Runs argv[0] with the arguments, waits; returns the exit status (128 + signal when killed).
// quiet: stdout and stderr go to /dev/null. stdin_text: written to the program's stdin.
int run_program(const std::vector<std::string>& argv, bool quiet, const std::string& stdin_text = "");
// A program built next to rayq-validate (in the tools build directory).
std::string tools_binary(const std::string& name);
// A fresh path in the system's temporary directory (the file is not created).
std::filesystem::path temporary_path(const std::string& suffix);

}  // namespace rayq::report
