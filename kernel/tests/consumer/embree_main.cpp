#include <rayq/embree.hpp>

#include <vector>

int main()
{
    const std::vector<rayq::Sphere<float>> spheres = {{{0, 0, 0}, 1}, {{0, 0, 5}, 1}};
    const rayq::embree::Scene<rayq::Sphere<float>> scene(spheres);
    const rayq::Ray<float> ray{{0, 0, -3}, {0, 0, 1}};
    const auto hit = scene.intersect(ray);
    return hit && hit->hit.t == 2.0f && hit->primID == 0 && scene.occluded(ray) ? 0 : 1;
}
