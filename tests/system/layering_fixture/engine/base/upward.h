// Fixture of layering_test_catches_upward: a base file including the run layer.
#pragma once

#include "engine/run/below.h"
