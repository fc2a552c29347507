// SPDX-License-Identifier: GPL-3.0-or-later
#define BOOST_TEST_MODULE spectral
#include "test_main.h"
