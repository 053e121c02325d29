// lrt/lrt.h: tangled from chapters/02-geometry.md. Edit the chapter, not this file.
#pragma once

// lrt.h includes
#include "lrt/core/base.h"
#include "lrt/core/geometry.h"
#include "lrt/core/transform.h"
#include "lrt/core/interaction.h"
#include "lrt/core/efloat.h"
#include "lrt/core/shape.h"
#include "lrt/shapes/disk.h"
#include "lrt/shapes/sphere.h"
#include "lrt/shapes/triangle.h"
#include "lrt/shapes/plyreader.h"
#include "lrt/core/slabtest.h"
#include "lrt/core/primitive.h"
#include "lrt/accelerators/bvh.h"
#include "lrt/accelerators/fastbvh.h"
#include "lrt/render/image.h"
#include "lrt/render/camera.h"
#include "lrt/render/renderer.h"
#include "lrt/render/bvhvisits.h"
