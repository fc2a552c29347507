// SPDX-License-Identifier: GPL-3.0-or-later
#define BOOST_TEST_MODULE init
#include "test_main.h"
