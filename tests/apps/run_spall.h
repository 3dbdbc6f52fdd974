// Runs the built `spall` binary with arguments and captures its exit code, stdout and stderr
// (stderr through a file, so `spall` sees a non-terminal stderr as in a batch job). The one
// helper every test that runs `spall` uses.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace spallkit::testing {

// The whole of a file (empty if it cannot be read): what a `spall` run wrote.
inline std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct SpallResult {
  int code = -1;
  std::string out, err;
  bool timed_out() const { return code == 124 || code == 137; }  // timeout(1)'s codes
};

// timeout_s > 0: killed after that many seconds (timeout(1); a hang then fails the test
// instead of stopping the test run).
inline SpallResult RunSpall(const std::string& args, int timeout_s = 0) {
  // Per process: ctest runs every TEST of a program as its own process, in parallel.
  const std::string err_path = std::filesystem::temp_directory_path() /
                               ("spall_cli_err_" + std::to_string(::getpid()) + ".txt");
  const std::string limit =
      timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : std::string();
  const std::string cmd = limit + SPALLKIT_SPALL_EXE + " " + args + " 2>" + err_path;
  SpallResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = ReadTextFile(err_path);
  std::filesystem::remove(err_path);
  return r;
}

// Same, with stdout and stderr in one string (stdout first); *code is the exit status.
inline std::string RunSpall(const std::string& args, int* code) {
  const SpallResult r = RunSpall(args);
  *code = r.code;
  return r.out + r.err;
}

}  // namespace spallkit::testing
