// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Included once per test executable (by test_<suite>_main.cpp) after BOOST_TEST_MODULE is defined.
// In Debug builds a global fixture traps invalid operations and divisions by zero so that NaNs
// fail loudly, as geometry-central's and libigl's test suites do.
#ifndef SMC_TEST_MAIN_H
#define SMC_TEST_MAIN_H
#include <boost/test/unit_test.hpp>
#if !defined(NDEBUG) && defined(__GLIBC__)
#include <fenv.h>
struct Trap_floating_point_exceptions
{
  Trap_floating_point_exceptions() { feenableexcept(FE_INVALID | FE_DIVBYZERO); }
};
BOOST_TEST_GLOBAL_FIXTURE(Trap_floating_point_exceptions);
#endif
#endif
