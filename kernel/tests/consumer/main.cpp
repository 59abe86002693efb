#include <rayq/rayq.hpp>

int main()
{
    const rayq::Ray<double> ray{{0, 0, -3}, {0, 0, 1}};
    const auto hit = rayq::intersect(ray, rayq::Sphere<double>{{0, 0, 0}, 1});
    return hit && hit->t == 2.0 ? 0 : 1;
}
