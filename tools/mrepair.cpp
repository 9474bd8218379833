// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Entry point of the `mrepair` program: dispatches to the registered commands
// (tools/cmd_*.cpp). Usage errors exit 2, bad input 1, success 0.
#include "cli.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace {
// A command allocates and frees arrays of several MB per pass (read, inspect,
// repair, inspect, write). glibc serves blocks above its dynamic mmap
// threshold with fresh mmaps, so every pass pays page faults and zeroing
// again; on a VM that was a third of `mrepair inspect` on a 1M-face scan
// (7.6 s -> 4.2 s on a loaded 2-core VM, peak +7%). Keeping blocks up to
// the largest threshold glibc accepts (32 MiB on 64-bit) in the heap, and
// not trimming it, lets later passes reuse warm pages. The library itself
// does not touch allocator settings: this is the program's choice.
void keep_freed_memory_warm()
{
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024);
  mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024);
#endif
}

// MREPAIR_THREADS=N caps the threads every parallel stage uses (TBB's
// max_allowed_parallelism); unset or empty: all the machine has. For
// measuring what the threads gain, and for sharing a machine.
std::unique_ptr<tbb::global_control> limit_threads()
{
  const char* s = std::getenv("MREPAIR_THREADS");
  if (s == nullptr || *s == 0) return nullptr;
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(s, &end, 10);
  if (errno != 0 || *end != 0 || n < 1 || n > 4096)
    throw mrepair::cli::Usage_error(std::string("MREPAIR_THREADS must be a whole number from 1 to 4096, not '") +
                                    s + "'");
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(n));
}

void print_usage()
{
  auto commands = mrepair::cli::registry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return a.name < b.name; });
  std::cout << "usage: mrepair COMMAND INPUT [OUTPUT] [options] [--report FILE.json]\n\ncommands:\n";
  for (const auto& c : commands)
    std::cout << "  " << c.name << std::string(c.name.size() < 12 ? 12 - c.name.size() : 1, ' ')
              << c.summary << "\n";
  std::cout << "\n'mrepair COMMAND --help' describes a command's options.\n"
            << "MREPAIR_THREADS=N in the environment caps the threads (default: all).\n";
}
} // namespace

int main(int argc, char** argv)
{
  keep_freed_memory_warm();
  std::unique_ptr<tbb::global_control> threads;
  try {
    threads = limit_threads();
  } catch (const mrepair::cli::Usage_error& e) {
    std::cerr << "mrepair: " << e.what() << "\n";
    return 2;
  }
  if (argc < 2) {
    print_usage();
    return 2;
  }
  std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    print_usage();
    return 0;
  }
  for (const auto& c : mrepair::cli::registry()) {
    if (c.name != name) continue;
    try {
      return c.run(argc - 1, argv + 1);
    } catch (const mrepair::cli::Usage_error& e) {
      std::cerr << "mrepair " << name << ": " << e.what() << "\n";
      return 2;
    } catch (const std::bad_alloc&) {
      std::cerr << "mrepair " << name << ": out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "mrepair " << name << ": internal error: " << e.what() << "\n";
      return 3;
    }
  }
  std::cerr << "mrepair: unknown command '" << name << "' (see mrepair --help)\n";
  return 2;
}
