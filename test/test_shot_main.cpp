// SPDX-License-Identifier: GPL-3.0-or-later
#define BOOST_TEST_MODULE shot
#include "test_main.h"
