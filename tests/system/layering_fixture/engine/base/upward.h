// Fixture of the layering_catches_upward_include test: a base file including the run layer.
#pragma once

#include "engine/run/below.h"
