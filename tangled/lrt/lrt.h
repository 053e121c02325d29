// lrt/lrt.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// lrt.h includes
#include "lrt/core/base.h"
#include "lrt/core/geometry.h"
// lrt.h includes
#include "lrt/core/transform.h"
#include "lrt/core/interaction.h"
// lrt.h includes
#include "lrt/core/efloat.h"
#include "lrt/core/shape.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/sphere.h"
// lrt.h includes
#include "lrt/shapes/triangle.h"
// lrt.h includes
#include "lrt/shapes/plyreader.h"
// lrt.h includes
#include "lrt/core/slabtest.h"
// lrt.h includes
#include "lrt/core/primitive.h"
// lrt.h includes
#include "lrt/accelerators/bvh.h"
// lrt.h includes
#include "lrt/accelerators/fastbvh.h"
// lrt.h includes
#include "lrt/render/image.h"
#include "lrt/render/camera.h"
#include "lrt/render/renderer.h"
#include "lrt/render/bvhvisits.h"
