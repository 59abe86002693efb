#include <rayq/rayq.hpp>

#include <cstdio>

int main()
{
    using namespace rayq;
    const Ray<double> ray{{0, 0, -5}, {0, 0, 1}};  // origin, direction (tmin = 0, tmax = inf)
    const Cylinder<double> can = Cylinder<double>::from_center({0, 0, 0}, {0, 0, 1}, 1.0, 2.0, Caps::both);

    if (!validate(can)) return 1;
    if (const auto hit = intersect(accurate, ray, can)) {  // closest hit, or std::nullopt
        std::printf("t = %g, part = %s, front face = %d\n", hit->t, hit->part == Part::cap0 ? "cap0" : "other",
                    hit->front_face);
        const bool blocked = occluded(ray, can);  // any hit, no record; default policy
        return blocked && hit->t == 3.0 ? 0 : 1;
    }
    return 1;
}
