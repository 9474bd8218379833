// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// libFuzzer target: the file readers of io.h (see fuzz_read.h for the input layout).
#include "fuzz_main.h"
#include "fuzz_read.h"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace {
// one scratch directory per process, in memory when /dev/shm exists; removed at exit
struct Temp_dir
{
  std::string path;
  Temp_dir()
  {
    const char* tmp = std::getenv("TMPDIR");
    path = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : (tmp ? tmp : "/tmp");
    path += "/mrepair_fuzz_read.XXXXXX";
    if (!mkdtemp(&path[0])) std::abort();
  }
  ~Temp_dir()
  {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const Temp_dir dir;
  mrepair_fuzz::report_violation(mrepair_fuzz::run_read(data, size, dir.path));
  return 0;
}
