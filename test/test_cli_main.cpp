// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Tests of the comap command-line tool (build/bin/comap), run as a separate process.
#define BOOST_TEST_MODULE cli
#include "test_main.h"
