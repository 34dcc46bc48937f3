#pragma once
// Forwarding header: ScratchDir lives in fixtures.h.
#include "fixtures.h"
using fixtures::ScratchDir;
