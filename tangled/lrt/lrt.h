// lrt/lrt.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// lrt.h includes
#include "lrt/core/base.h"
#include "lrt/core/geometry.h"
// lrt.h includes
#include "lrt/core/transform.h"
#include "lrt/core/interaction.h"
