// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// doc_snippets: the C++ programs of the manual's pages, compiled together to check that they
// compile (see doc/CMakeLists.txt); they are not run.

int main() { return 0; }
