#pragma once
// Forwarding header: expectInputError lives in fixtures.h.
#include "fixtures.h"
using fixtures::expectInputError;
