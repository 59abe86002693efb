// rayq-demo: a few rays against every primitive, in float and double, under every precision
// policy, printed as a table. The rays are chosen so the answers can be checked by eye
// (the "expect" comments give them).
#include <rayq/rayq.hpp>

#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

namespace {

const char usage[] =
    "usage: rayq-demo [--help]\n"
    "\n"
    "Intersects a handful of rays with each rayq primitive (sphere, plane, disk, parallelogram,\n"
    "triangle, open and capped cylinder), in float and double, under each precision policy\n"
    "(fast, stable, accurate), and prints one row per hit or miss:\n"
    "  primitive, ray, type, policy, t, point, normal, front_face, part.\n";

// A ray in double; each row converts it to the scalar type under test.
struct RayCase {
    double ox, oy, oz, dx, dy, dz;
    const char* expect;  // what an exact computation gives, for the reader
};

template <class T> constexpr const char* type_name() { return sizeof(T) == 4 ? "float" : "double"; }
constexpr const char* policy_name(rayq::fast_policy) { return "fast"; }
constexpr const char* policy_name(rayq::stable_policy) { return "stable"; }
constexpr const char* policy_name(rayq::accurate_policy) { return "accurate"; }

const char* part_name(rayq::Part p)
{
    switch (p) {
    case rayq::Part::surface: return "surface";
    case rayq::Part::cap0: return "cap0";
    case rayq::Part::cap1: return "cap1";
    }
    return "?";
}

template <class T>
void format_vec(char* buf, std::size_t n, const rayq::Vec3<T>& v)
{
    // + 0.0 prints a negated zero component (from facing the normal to the ray) as 0.
    std::snprintf(buf, n, "(%.6g, %.6g, %.6g)", double(v.x) + 0.0, double(v.y) + 0.0, double(v.z) + 0.0);
}

template <class T, class Policy, class Prim>
void row(const char* name, int index, const RayCase& rc, Policy policy, const Prim& prim)
{
    const rayq::Ray<T> ray{{T(rc.ox), T(rc.oy), T(rc.oz)}, {T(rc.dx), T(rc.dy), T(rc.dz)}};
    std::printf("%-15s %3d  %-6s  %-8s  ", name, index, type_name<T>(), policy_name(policy));
    if (const auto hit = rayq::intersect(policy, ray, prim)) {
        char p[64], n[64];
        format_vec(p, sizeof p, hit->point);
        format_vec(n, sizeof n, hit->normal);
        std::printf("%-22.*g  %-28s  %-28s  %-5s  %s\n", std::numeric_limits<T>::max_digits10, double(hit->t), p, n,
                    hit->front_face ? "yes" : "no", part_name(hit->part));
    } else {
        std::printf("miss\n");
    }
}

// Every policy and both scalar types for each ray; make(T) builds the primitive in type T.
template <class Make, std::size_t N>
void primitive(const char* name, const RayCase (&rays)[N], Make make)
{
    for (std::size_t i = 0; i < N; ++i) {
        std::printf("%-15s %3zu  ray (%g, %g, %g) + t(%g, %g, %g); expect %s\n", name, i, rays[i].ox, rays[i].oy,
                    rays[i].oz, rays[i].dx, rays[i].dy, rays[i].dz, rays[i].expect);
        const auto pf = make(float{});
        const auto pd = make(double{});
        row<float>(name, int(i), rays[i], rayq::fast, pf);
        row<float>(name, int(i), rays[i], rayq::stable, pf);
        row<float>(name, int(i), rays[i], rayq::accurate, pf);
        row<double>(name, int(i), rays[i], rayq::fast, pd);
        row<double>(name, int(i), rays[i], rayq::stable, pd);
        row<double>(name, int(i), rays[i], rayq::accurate, pd);
    }
    std::printf("\n");
}

void run()
{
    using namespace rayq;
    std::printf("%-15s %3s  %-6s  %-8s  %-22s  %-28s  %-28s  %-5s  %s\n", "primitive", "ray", "type", "policy", "t",
                "point", "normal", "front", "part");
    std::printf("%s\n", std::string(150, '-').c_str());

    // Unit sphere at the origin.
    const RayCase sphere_rays[] = {
        {0, 0, -5, 0, 0, 1, "t=4 at (0,0,-1), front, surface"},
        {0.6, 0, -5, 0, 0, 1, "t=4.2 at (0.6,0,-0.8), front, surface"},
        {0, 0, -5, 0, 0, 2, "t=2 at (0,0,-1) (direction not unit)"},
        {0, 0, 0, 1, 0, 0, "t=1 at (1,0,0), back (from inside), normal (-1,0,0)"},
        {0, 2, -5, 0, 0, 1, "miss (passes beside)"},
        {0, 0, 5, 0, 0, 1, "miss (sphere behind the ray)"},
    };
    primitive("sphere", sphere_rays, [](auto t) {
        using T = decltype(t);
        return Sphere<T>{{T(0), T(0), T(0)}, T(1)};
    });

    // The plane z = 0, front side +z.
    const RayCase plane_rays[] = {
        {1, 2, 5, 0, 0, -1, "t=5 at (1,2,0), front"},
        {0, 0, 4, 3, 0, -4, "t=1 at (3,0,0), front"},
        {0, 0, -3, 0, 0, 1, "t=3 at (0,0,0), back, normal (0,0,-1)"},
        {0, 0, 1, 1, 0, 0, "miss (parallel)"},
        {0, 0, 1, 0, 0, 1, "miss (pointing away)"},
    };
    primitive("plane", plane_rays, [](auto t) {
        using T = decltype(t);
        return Plane<T>{{T(0), T(0), T(0)}, {T(0), T(0), T(1)}};
    });

    // Unit disk in z = 0, front side +z.
    const RayCase disk_rays[] = {
        {0.5, 0, 2, 0, 0, -1, "t=2 at (0.5,0,0), front"},
        {0, 0.5, -1, 0, 0, 1, "t=1 at (0,0.5,0), back"},
        {1, 0, 2, 0, 0, -1, "t=2 at (1,0,0), on the rim (counts)"},
        {1.5, 0, 2, 0, 0, -1, "miss (outside the radius)"},
    };
    primitive("disk", disk_rays, [](auto t) {
        using T = decltype(t);
        return Disk<T>{{T(0), T(0), T(0)}, {T(0), T(0), T(1)}, T(1)};
    });

    // The rectangle [0,2]x[0,1] in z = 0, front side +z.
    const RayCase parallelogram_rays[] = {
        {1, 0.5, 3, 0, 0, -1, "t=3 at (1,0.5,0), front"},
        {0.5, 0.5, -2, 0, 0, 1, "t=2 at (0.5,0.5,0), back"},
        {0, 0, 1, 1, 1, -1, "t=1 at (1,1,0), on edge1's far edge (counts)"},
        {2.5, 0.5, 3, 0, 0, -1, "miss (beyond edge0)"},
    };
    primitive("parallelogram", parallelogram_rays, [](auto t) {
        using T = decltype(t);
        return Parallelogram<T>{{T(0), T(0), T(0)}, {T(2), T(0), T(0)}, {T(0), T(1), T(0)}};
    });

    // Triangle (0,0,0), (1,0,0), (0,1,0), counter-clockwise seen from +z.
    const RayCase triangle_rays[] = {
        {0.25, 0.25, 1, 0, 0, -1, "t=1 at (0.25,0.25,0), front"},
        {0.25, 0.25, -1, 0, 0, 1, "t=1 at (0.25,0.25,0), back"},
        {0.5, 0.5, 1, 0, 0, -1, "t=1 at (0.5,0.5,0), on the hypotenuse (counts)"},
        {0.75, 0.75, 1, 0, 0, -1, "miss (beyond the hypotenuse)"},
    };
    primitive("triangle", triangle_rays, [](auto t) {
        using T = decltype(t);
        return Triangle<T>{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}, {T(0), T(1), T(0)}};
    });

    // Radius 1 about the z axis, z in [-2, 2]; open, then capped.
    const RayCase open_rays[] = {
        {-5, 0, 0, 1, 0, 0, "t=4 at (-1,0,0), front, surface"},
        {0, 0, 0, 0, 1, 0, "t=1 at (0,1,0), back, surface"},
        {0, 0, 5, 0.25, 0, -1, "t=4 at (1,0,1), back (in through the open end), surface"},
        {0, 0, -5, 0, 0, 1, "miss (along the axis, through both open ends)"},
        {-5, 0, 3, 1, 0, 0, "miss (above the top)"},
    };
    primitive("cylinder", open_rays, [](auto t) {
        using T = decltype(t);
        return Cylinder<T>::from_center({T(0), T(0), T(0)}, {T(0), T(0), T(1)}, T(1), T(2));
    });
    const RayCase capped_rays[] = {
        {-5, 0, 0, 1, 0, 0, "t=4 at (-1,0,0), front, surface"},
        {0, 0, 0, 0, 1, 0, "t=1 at (0,1,0), back, surface"},
        {0, 0, 5, 0.25, 0, -1, "t=3 at (0.75,0,2), front, cap1"},
        {0, 0, -5, 0, 0, 1, "t=3 at (0,0,-2), front, cap0"},
        {-5, 0, 3, 1, 0, 0, "miss (above the top)"},
    };
    primitive("cylinder+caps", capped_rays, [](auto t) {
        using T = decltype(t);
        return Cylinder<T>::from_center({T(0), T(0), T(0)}, {T(0), T(0), T(1)}, T(1), T(2), Caps::both);
    });
}

}  // namespace

int main(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
            std::fputs(usage, stdout);
            return 0;
        }
        std::fprintf(stderr, "rayq-demo: unknown option '%s'\n%s", argv[i], usage);
        return 2;
    }
    run();
    return 0;
}
