// lrt/render/bvhvisits.cpp: tangled from chapters/08-rendering.md. Edit the chapter, not this file.
#include "lrt/render/bvhvisits.h"
#include "lrt/core/slabtest.h"

#include <algorithm>

namespace lrt {

// BVH Visits Definitions
int CountNodeVisits(const BVHAccel &bvh, const Ray &ray,
                    SurfaceInteraction *isect, bool *hit) {
    const std::vector<LinearBVHNode> &nodes = bvh.Nodes();
    const auto &primitives = bvh.Primitives();
    *hit = false;
    if (nodes.empty()) return 0;
    Vector3f invDir(1 / ray.d.x, 1 / ray.d.y, 1 / ray.d.z);
    int dirIsNeg[3] = {invDir.x < 0, invDir.y < 0, invDir.z < 0};
    int toVisit[maxBVHDepth];
    int toVisitOffset = 0, current = 0, visits = 0;
    while (true) {
        const LinearBVHNode &node = nodes[current];
        ++visits;
        if (node.bounds.IntersectP(ray, invDir, dirIsNeg)) {
            if (node.nPrimitives > 0) {
                for (int i = 0; i < node.nPrimitives; ++i)
                    if (primitives[node.primitivesOffset + i]->Intersect(
                            ray, isect))
                        *hit = true;
                if (toVisitOffset == 0) break;
                current = toVisit[--toVisitOffset];
            } else if (dirIsNeg[node.axis]) {
                toVisit[toVisitOffset++] = current + 1;
                current = node.secondChildOffset;
            } else {
                toVisit[toVisitOffset++] = node.secondChildOffset;
                current = current + 1;
            }
        } else {
            if (toVisitOffset == 0) break;
            current = toVisit[--toVisitOffset];
        }
    }
    return visits;
}
RGB HeatColor(Float v) {
    static const Float stops[5][3] = {{0.03, 0.02, 0.10},
                                      {0.33, 0.07, 0.50},
                                      {0.80, 0.18, 0.36},
                                      {0.98, 0.56, 0.12},
                                      {1.00, 0.97, 0.70}};
    if (!(v > 0)) v = 0;
    if (v > 1) v = 1;
    Float x = v * 4;
    int i = std::min(int(x), 3);
    Float f = x - i;
    Float c[3];
    for (int k = 0; k < 3; ++k)
        c[k] = InverseGammaCorrect((1 - f) * stops[i][k] + f * stops[i + 1][k]);
    return RGB(c[0], c[1], c[2]);
}
Image RenderNodeVisits(const BVHAccel &bvh, const PinholeCamera &camera,
                       int maxVisits, std::vector<int> *visits) {
    Image image(camera.width, camera.height);
    if (visits) visits->assign(size_t(camera.width) * camera.height, 0);
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            Point2f pRaster(x + Float(0.5), y + Float(0.5));
            Ray ray = camera.GenerateRay(pRaster);
            SurfaceInteraction isect;
            bool hit;
            int count = CountNodeVisits(bvh, ray, &isect, &hit);
            if (visits) (*visits)[size_t(y) * camera.width + x] = count;
            image(x, y) = HeatColor(Float(count) / Float(maxVisits));
        }
    return image;
}

}  // namespace lrt
