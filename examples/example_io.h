// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The file reading and writing the examples share, so that each one shows its
// library call and not the error handling of its files.
#ifndef MREPAIR_EXAMPLE_IO_H
#define MREPAIR_EXAMPLE_IO_H

#include <mrepair/io.h>

#include <iostream>

/// reads `path` into `mesh` with `mrepair::read_polygon_mesh`; says why on
/// std::cerr and returns false when it cannot.
template <typename Mesh>
bool read_mesh(const char* path, Mesh& mesh)
{
  const mrepair::Io_result io = mrepair::read_polygon_mesh(path, mesh);
  if (mrepair::succeeded(io.status)) return true;
  std::cerr << "cannot read " << path << ": " << io.message << "\n";
  return false;
}

/// writes `mesh` to `path` with `mrepair::write_polygon_mesh`; says why on
/// std::cerr and returns false when it cannot.
template <typename Mesh>
bool write_mesh(const char* path, const Mesh& mesh)
{
  const mrepair::Io_result out = mrepair::write_polygon_mesh(path, mesh);
  if (mrepair::succeeded(out.status)) return true;
  std::cerr << "cannot write " << path << ": " << out.message << "\n";
  return false;
}

#endif // MREPAIR_EXAMPLE_IO_H
