// Fixture of layering_test_catches_upward: a run file including base, which is allowed.
#pragma once

#include "engine/base/upward.h"
