// rayq::embree — rayq primitives as Embree 3 user geometry: Embree's BVH culls, rayq decides.
//
//     rayq::embree::Scene<rayq::Sphere<float>, rayq::accurate_policy> scene(spheres);
//     if (auto h = scene.intersect(ray)) ... h->hit (rayq's Hit: t, normal, part, t_error),
//                                            h->primID (index into `spheres`), h->geomID, h->tfar
//     bool blocked = scene.occluded(ray);
//
// Lower level, for Embree scenes of your own (several rayq geometries, native Embree geometry):
//
//     rayq::embree::UserGeometry<rayq::Cylinder<double>, rayq::stable_policy> cans(device, cylinders);
//     const unsigned id = cans.attach(my_scene);         // then rtcCommitScene(my_scene)
//     rayq::embree::QueryContext<double> ctx(ray);       // the query in the primitives' precision
//     RTCRayHit rh = ctx.embree_ray();
//     rtcIntersect1(my_scene, ctx.context(), &rh);
//     if (rh.hit.geomID == id) auto hit = cans.hit_record(ctx);  // from the crossing the callback kept
//     (or cans.hit_record(ray, rh.hit.primID): the same record, computed again)
//
// Answers: with a QueryContext, the closest hit is exactly what rayq's scalar loop over every
// primitive gives — the same t bit for bit (kept in T: Embree's tfar is float, rounded up for
// double), the same primitive, the lowest (geomID, primID) among equal t — because (1) boxes are
// conservative for the policy (bounds.hpp), so Embree never culls a primitive rayq would hit,
// (2) each candidate is decided by rayq's own crossings() on the T-precision ray, in the window
// (tmin, next_up(best t)) exactly as rayq::Scene narrows it, and (3) only the winner gets a full
// hit record, from rayq::intersect on the original ray. Without a QueryContext (a plain
// RTCIntersectContext, or ray packets) the callbacks still work on Embree's float ray and report
// tfar, Ng (the outward normal), primID and geomID; rayq's Hit is then hit_record(ray, primID).
//
// Floating-point mode: Embree recommends FTZ/DAZ for its own speed; rayq's certified and exact
// arithmetic needs gradual underflow. A QueryContext switches FTZ/DAZ off for its lifetime (the
// whole query, Embree's traversal included) and restores the caller's mode when it ends; without
// one (a plain context, packets) each callback switches them off while rayq decides and restores
// them. Once per query rather than per call, and the record is covered too: the MXCSR read
// (stmxcsr, microcoded) held half of the callback's own samples (perf, 100,000 spheres, `stable`:
// 4% of all), and the record had been built in the caller's mode (DAZ read a subnormal as 0).
#pragma once

#include <rayq/embree/bounds.hpp>
#include <rayq/rayq.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <embree3/rtcore.h>

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#define RAYQ_EMBREE_HAS_MXCSR 1
#else
#define RAYQ_EMBREE_HAS_MXCSR 0
#endif

namespace rayq::embree {

struct Options {
    // Largest |coordinate| of any ray origin, when rays may start much farther from the world
    // origin than the primitives lie (the boxes' padding scales with it: bounds.hpp). 0: origins
    // are no farther out than the primitives' own coordinates (times a small factor).
    double origin_bound = 0;
    // RTC_SCENE_FLAG_ROBUST for the Scene below (slower traversal; not needed for exactness: the
    // padding already covers Embree's slab-test rounding).
    bool robust = false;
    RTCBuildQuality build_quality = RTC_BUILD_QUALITY_MEDIUM;
    // Passed to rtcNewDevice by Scene (e.g. "threads=1"); nullptr: Embree's defaults.
    const char* device_config = nullptr;
    // At most this many rayq primitives per leaf of Scene's BVH (Embree's device option
    // object_accel_max_leaf_size, whose default is 1). A leaf calls back once per primitive, so
    // larger leaves trade node visits in Embree's traversal for rayq decisions: a win once the
    // BVH and the primitives outgrow the caches. 0: automatic, 1 below 32,768 primitives and 3
    // from there (spheres, fresh rays, AMD EPYC with a 1 MB L2; leaf 3 over leaf 1, `accurate`:
    // 0.87x at 1,000 spheres, 0.92x at 10,000, 0.99x at 30,000, 1.13-1.35x at 100,000).
    unsigned max_leaf_size = 0;
};

// Options::max_leaf_size's automatic choice for a scene of n primitives (see there).
inline unsigned automatic_max_leaf_size(std::size_t n) { return n < 32768 ? 1 : 3; }

namespace detail {

// Switches flush-to-zero and denormals-are-zero off for its lifetime (rayq's error-free
// transformations and certified bounds assume IEEE gradual underflow).
class IeeeArithmetic {
public:
#if RAYQ_EMBREE_HAS_MXCSR
    static constexpr unsigned ftz_daz = 0x8040u;  // MXCSR bit 15 (FTZ) and bit 6 (DAZ)
    IeeeArithmetic() : saved_(_mm_getcsr())
    {
        if (saved_ & ftz_daz) _mm_setcsr(saved_ & ~ftz_daz);
    }
    ~IeeeArithmetic()
    {
        if (saved_ & ftz_daz) _mm_setcsr(saved_);
    }

private:
    unsigned saved_;
#endif
};

template <class T>
inline float to_tfar(T t)
{
    return round_up_to_float(double(t));  // exact for float; for double the float at or above t
}

}  // namespace detail

template <class T>
struct QueryContext;

namespace detail {

// The QueryContexts alive on this thread, innermost first (linked through `outer`): how a callback
// recognises that Embree's context pointer is one of ours. (Tagging the context's filter pointer
// instead would trip an assertion in Debian's Embree, which is built with assertions on, for
// scenes without RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION.)
template <class T>
inline thread_local QueryContext<T>* innermost_query = nullptr;

}  // namespace detail

// Rays from farther out than this are answered without Embree (see QueryContext::embree_ray).
inline constexpr double embree_large_origin = detail::embree_large / 2;

// One closest-hit or any-hit query's state; its `embree` member is the intersect context handed
// to rtcIntersect1/rtcOccluded1. Holds the query in the primitives' precision T and the best hit
// so far. One ray, not packets. Create it on the stack, on the thread that traces: it registers
// itself for that thread until destroyed (contexts nest; destroy them in reverse order), and
// keeps that thread's FTZ/DAZ off meanwhile (restored when it is destroyed).
template <class T>
struct QueryContext {
    detail::IeeeArithmetic ieee;  // FTZ/DAZ off while the query lives (first member: set before anything runs)
    RTCIntersectContext embree;
    Ray<T> ray;                // the query as given (Embree's copy is float)
    T window_end;              // candidates must have t < window_end: ray.tmax, then next_up(best t)
    T t;                       // the best hit's t (when geomID != RTC_INVALID_GEOMETRY_ID)
    unsigned geomID;
    unsigned primID;
    float tfar_written;        // the tfar last written into Embree's ray by a rayq callback
    Crossing<T> crossing{};    // the best hit's crossing, as rayq's leading_crossings() gave it
    bool crossing_is_first = false;  // no crossing before it: its record needs no second look

    explicit QueryContext(const Ray<T>& query)
        : ray(query), window_end(query.tmax), t(query.tmax), geomID(RTC_INVALID_GEOMETRY_ID), primID(RTC_INVALID_GEOMETRY_ID),
          tfar_written(detail::to_tfar(query.tmax)), outer_(detail::innermost_query<T>)
    {
        rtcInitIntersectContext(&embree);
        detail::innermost_query<T> = this;
    }
    ~QueryContext() { detail::innermost_query<T> = outer_; }
    QueryContext(const QueryContext&) = delete;
    QueryContext& operator=(const QueryContext&) = delete;

    RTCIntersectContext* context() { return &embree; }
    bool found() const { return geomID != RTC_INVALID_GEOMETRY_ID; }

    // Embree's float copy of the query: origin and direction rounded to nearest, the window
    // rounded outward (the decisions use `ray`, in T). nullopt when the float ray is unusable
    // (overflow, an underflowing direction) or starts before 0, which Embree's segments cannot.
    std::optional<RTCRayHit> embree_ray() const
    {
        if (!(ray.tmin >= T(0))) return std::nullopt;
        // Boxes are clamped to ±embree_large (bounds.hpp); an origin beyond it could reach a
        // clamped primitive without crossing its box.
        const double o_max = std::max({std::abs(double(ray.origin.x)), std::abs(double(ray.origin.y)), std::abs(double(ray.origin.z))});
        if (!(o_max <= embree_large_origin)) return std::nullopt;
        const Ray<float> f{{float(ray.origin.x), float(ray.origin.y), float(ray.origin.z)},
                           {float(ray.direction.x), float(ray.direction.y), float(ray.direction.z)},
                           rayq::embree::detail::round_down_to_float(double(ray.tmin)), tfar_written};
        if (!usable(f)) return std::nullopt;
        RTCRayHit rh;
        rh.ray.org_x = f.origin.x, rh.ray.org_y = f.origin.y, rh.ray.org_z = f.origin.z;
        rh.ray.dir_x = f.direction.x, rh.ray.dir_y = f.direction.y, rh.ray.dir_z = f.direction.z;
        rh.ray.tnear = f.tmin, rh.ray.tfar = f.tmax;
        rh.ray.time = 0;
        rh.ray.mask = ~0u;  // Debian's Embree is built with ray masks: 0 would hit nothing
        rh.ray.id = 0, rh.ray.flags = 0;
        rh.hit.geomID = rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.Ng_x = rh.hit.Ng_y = rh.hit.Ng_z = 0, rh.hit.u = rh.hit.v = 0;
        return rh;
    }

    // The QueryContext behind an Embree context, or nullptr for a plain one (or another T's).
    static QueryContext* from(const RTCIntersectContext* c)
    {
        for (QueryContext* q = detail::innermost_query<T>; q; q = q->outer_)
            if (&q->embree == c) return q;
        return nullptr;
    }

private:
    QueryContext* outer_;
};

// Registers `primitives` as one Embree user geometry (one Embree primitive each, primID = index).
// Prim: any rayq primitive with a world_box overload (bounds.hpp); Policy: fast, stable or
// accurate, the policy rayq decides with. Owns its primitives; not movable (Embree keeps `this`).
template <class Prim, class Policy = default_policy>
class UserGeometry {
    static_assert(is_primitive_v<Prim>, "rayq::embree::UserGeometry: Prim must be a rayq primitive");
    static_assert(is_policy_v<Policy>, "rayq::embree::UserGeometry: Policy must be rayq::fast_policy, stable_policy or accurate_policy");

public:
    using scalar_type = scalar_t<Prim>;
    using T = scalar_type;

    UserGeometry(RTCDevice device, std::vector<Prim> primitives, Policy policy = {}, const Options& options = {})
        : primitives_(std::move(primitives)), policy_(policy)
    {
        boxes_.reserve(primitives_.size());
        for (const Prim& p : primitives_) boxes_.push_back(embree_bounds<Policy>(p, options.origin_bound));
        geometry_ = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        if (!geometry_) throw std::runtime_error("rayq::embree: rtcNewGeometry(RTC_GEOMETRY_TYPE_USER) failed");
        rtcSetGeometryUserPrimitiveCount(geometry_, static_cast<unsigned>(primitives_.size()));
        rtcSetGeometryUserData(geometry_, this);
        rtcSetGeometryBoundsFunction(geometry_, &UserGeometry::bounds_callback, nullptr);
        rtcSetGeometryIntersectFunction(geometry_, &UserGeometry::intersect_callback);
        rtcSetGeometryOccludedFunction(geometry_, &UserGeometry::occluded_callback);
        rtcCommitGeometry(geometry_);
    }
    ~UserGeometry() { rtcReleaseGeometry(geometry_); }
    UserGeometry(const UserGeometry&) = delete;
    UserGeometry& operator=(const UserGeometry&) = delete;

    // Attaches to `scene` (commit the scene afterwards) and returns the geomID.
    unsigned attach(RTCScene scene) { return geomID_ = rtcAttachGeometry(scene, geometry_); }

    RTCGeometry handle() const { return geometry_; }
    const std::vector<Prim>& primitives() const { return primitives_; }
    const RTCBounds& bounds(std::size_t primID) const { return boxes_.at(primID); }
    Policy policy() const { return policy_; }

    // rayq's hit record for primitive primID on `ray` (what the scalar intersect gives), with the
    // fields asked for. Both overloads build it with FTZ/DAZ off, whatever the caller's mode.
    std::optional<Hit<T>> hit_record(const Ray<T>& ray, unsigned primID, HitFields fields = HitFields::all) const
    {
        [[maybe_unused]] detail::IeeeArithmetic ieee;
        return ::rayq::intersect(policy_, ray, primitives_.at(primID), fields);
    }

    // The same record for the closest hit of a query traced with `found`, when that hit is this
    // geometry's (with other geometry in the scene, check Embree's rh.hit.geomID first: a native
    // hit nearer than rayq's leaves the context as it was); nullopt when the context holds none of
    // this geometry's. Built from the crossing the callback kept, without computing the
    // primitive's crossings again when none came before it (the scalar intersect() then builds it
    // from that crossing too: write_first_hit with no earlier crossing to cover); otherwise as above.
    std::optional<Hit<T>> hit_record(const QueryContext<T>& found, HitFields fields = HitFields::all) const
    {
        std::optional<Hit<T>> out;
        if (!write_hit_record(found, fields, out.emplace())) out.reset();
        return out;
    }

    // The same record written into `out` (a fresh Hit, where the caller keeps it); false, `out`
    // unspecified, where hit_record gives nullopt. Not built in a Hit and copied: GCC copies a
    // record in 16-byte loads of fields just stored as 8-, 4- and 2-byte pieces (failed store
    // forwarding, as in rayq::intersect), and Scene::intersect copied it twice more.
    bool write_hit_record(const QueryContext<T>& found, HitFields fields, Hit<T>& out) const
    {
        if (!found.found() || found.geomID != geomID_) return false;
        if (!found.crossing_is_first) {
            const std::optional<Hit<T>> h = hit_record(found.ray, found.primID, fields);
            if (h) out = *h;
            return h.has_value();
        }
        [[maybe_unused]] detail::IeeeArithmetic ieee;  // (off already while `found` lives on this thread)
        ::rayq::detail::write_first_hit(policy_, found.ray, primitives_.at(found.primID), found.crossing, false, fields, out);
        return true;
    }

private:
    // The first crossing of primitive i inside (ray.tmin, tmax) and whether no crossing precedes
    // it: the scalar intersect()'s own core (leading_crossings: under `accurate` only the first
    // root in the window is rounded), no record. Answers in a bool, the crossing through `out`:
    // returned as std::optional, GCC stored its flag as a byte and read it back within eight
    // bytes, a store-forwarding stall on every miss, and the window ray was copied for the call
    // (100,000 spheres, `stable`, 6 paired rounds: 0.887x -> 0.907x Embree, nearest 0.962x -> 0.988x).
    struct FirstCrossing {
        Crossing<T> crossing;
        bool is_first;
    };
    bool first_crossing(const Ray<T>& ray, T tmax, unsigned i, FirstCrossing& out) const
    {
        const Ray<T> window{ray.origin, ray.direction, ray.tmin, tmax};
        const auto cs = ::rayq::detail::leading_crossings(policy_, window, primitives_[i]);
        const Crossing<T>* c = ::rayq::detail::first_in_window(window, cs);
        if (!c) return false;
        out = FirstCrossing{*c, c == cs.begin()};
        return true;
    }

    static void bounds_callback(const RTCBoundsFunctionArguments* args)
    {
        const auto* self = static_cast<const UserGeometry*>(args->geometryUserPtr);
        *args->bounds_o = self->boxes_[args->primID];
    }

    static Ray<T> ray_from_lane(RTCRayN* ray, unsigned n, unsigned i)
    {
        return {{T(RTCRayN_org_x(ray, n, i)), T(RTCRayN_org_y(ray, n, i)), T(RTCRayN_org_z(ray, n, i))},
                {T(RTCRayN_dir_x(ray, n, i)), T(RTCRayN_dir_y(ray, n, i)), T(RTCRayN_dir_z(ray, n, i))},
                T(RTCRayN_tnear(ray, n, i)),
                T(RTCRayN_tfar(ray, n, i))};
    }

    Vec3<float> outward_normal_at(const Ray<T>& ray, unsigned i, const Crossing<T>& c) const
    {
        const Vec3<T> n = outward_normal(primitives_[i], point_at(ray, c.t), c.part);
        return {float(n.x), float(n.y), float(n.z)};
    }

    static void intersect_callback(const RTCIntersectFunctionNArguments* args)
    {
        const auto* self = static_cast<const UserGeometry*>(args->geometryUserPtr);
        const unsigned prim = args->primID;  // a valid primitive: invalid ones have inverted boxes, which Embree drops
        if (QueryContext<T>* ctx = args->N == 1 ? QueryContext<T>::from(args->context) : nullptr) {  // FTZ/DAZ already off
            if (!args->valid[0]) return;
            RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
            T tmax = ctx->window_end;
            // Another geometry (Embree native) lowered tfar below what we wrote: its hit is nearer.
            if (rh->ray.tfar != ctx->tfar_written && T(rh->ray.tfar) < tmax) tmax = T(rh->ray.tfar);
            FirstCrossing found;
            if (!self->first_crossing(ctx->ray, tmax, prim, found)) return;
            const Crossing<T>* c = &found.crossing;
            // Equal t: the lower (geomID, primID) wins, as the scalar loop's first index does.
            if (ctx->found() && !(c->t < ctx->t || (c->t == ctx->t && std::make_pair(args->geomID, prim) <
                                                                          std::make_pair(ctx->geomID, ctx->primID))))
                return;
            ctx->t = c->t;
            ctx->geomID = args->geomID;
            ctx->primID = prim;
            ctx->crossing = *c;
            ctx->crossing_is_first = found.is_first;
            ctx->window_end = rayq::detail::next_up(c->t);  // ties stay in the window (rayq::Scene does the same)
            ctx->tfar_written = detail::to_tfar(c->t);
            rh->ray.tfar = ctx->tfar_written;
            const Vec3<float> n = self->outward_normal_at(ctx->ray, prim, *c);
            rh->hit.Ng_x = n.x, rh->hit.Ng_y = n.y, rh->hit.Ng_z = n.z;
            rh->hit.u = rh->hit.v = 0;
            rh->hit.primID = prim;
            rh->hit.geomID = args->geomID;
            rh->hit.instID[0] = args->context->instID[0];
            return;
        }
        // A plain context or a packet: decide on Embree's float ray, lane by lane.
        [[maybe_unused]] detail::IeeeArithmetic ieee;  // FTZ/DAZ off while rayq decides
        RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
        RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
        for (unsigned i = 0; i < args->N; ++i) {
            if (!args->valid[i]) continue;
            const Ray<T> ray = ray_from_lane(rays, args->N, i);
            if (!usable(ray)) continue;
            FirstCrossing found;
            if (!self->first_crossing(ray, ray.tmax, prim, found)) continue;
            RTCRayN_tfar(rays, args->N, i) = detail::to_tfar(found.crossing.t);
            const Vec3<float> n = self->outward_normal_at(ray, prim, found.crossing);
            RTCHitN_Ng_x(hits, args->N, i) = n.x, RTCHitN_Ng_y(hits, args->N, i) = n.y, RTCHitN_Ng_z(hits, args->N, i) = n.z;
            RTCHitN_u(hits, args->N, i) = 0, RTCHitN_v(hits, args->N, i) = 0;
            RTCHitN_primID(hits, args->N, i) = prim;
            RTCHitN_geomID(hits, args->N, i) = args->geomID;
            RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
        }
    }

    static void occluded_callback(const RTCOccludedFunctionNArguments* args)
    {
        const auto* self = static_cast<const UserGeometry*>(args->geometryUserPtr);
        const unsigned prim = args->primID;  // valid, as in intersect_callback
        if (QueryContext<T>* ctx = args->N == 1 ? QueryContext<T>::from(args->context) : nullptr) {  // FTZ/DAZ already off
            FirstCrossing found;
            if (!args->valid[0] || !self->first_crossing(ctx->ray, ctx->ray.tmax, prim, found)) return;
            ctx->t = T(0);  // any hit: no t is computed
            ctx->geomID = args->geomID;
            ctx->primID = prim;
            reinterpret_cast<RTCRay*>(args->ray)->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded"
            return;
        }
        [[maybe_unused]] detail::IeeeArithmetic ieee;  // FTZ/DAZ off while rayq decides
        for (unsigned i = 0; i < args->N; ++i) {
            if (!args->valid[i]) continue;
            const Ray<T> ray = ray_from_lane(args->ray, args->N, i);
            FirstCrossing found;
            if (usable(ray) && self->first_crossing(ray, ray.tmax, prim, found)) RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
        }
    }

    std::vector<Prim> primitives_;
    std::vector<RTCBounds> boxes_;
    Policy policy_;
    RTCGeometry geometry_ = nullptr;
    unsigned geomID_ = RTC_INVALID_GEOMETRY_ID;
};

// The closest hit: rayq's record plus Embree's view of it.
template <class T>
struct EmbreeHit {
    Hit<T> hit;       // rayq::intersect(policy, ray, primitive[primID]): t, normal, part, t_error, ...
    unsigned geomID;  // Embree's geometry id (the Scene below has one geometry: 0)
    unsigned primID;  // index into the primitives given to the constructor
    float tfar;       // Embree's ray.tfar: hit.t, rounded up to float for double primitives
};

// The closest hit's t and primitive, without the record.
template <class T>
struct EmbreeRef {
    T t;
    unsigned geomID;
    unsigned primID;
    float tfar;
};

// A ready-made Embree device + scene holding one UserGeometry: build once, query many rays.
template <class Prim, class Policy = default_policy>
class Scene {
public:
    using T = scalar_t<Prim>;

    explicit Scene(std::vector<Prim> primitives, Policy policy = {}, const Options& options = {})
    {
        std::string config = options.device_config ? options.device_config : "";
        const unsigned leaf = options.max_leaf_size > 0 ? options.max_leaf_size : automatic_max_leaf_size(primitives.size());
        config = "object_accel_max_leaf_size=" + std::to_string(leaf) + (config.empty() ? "" : "," + config);
        device_ = rtcNewDevice(config.c_str());
        if (!device_) throw std::runtime_error("rayq::embree: rtcNewDevice failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
        const auto start = std::chrono::steady_clock::now();
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
        rtcSetSceneBuildQuality(scene_, options.build_quality);
        geometry_ = std::make_unique<UserGeometry<Prim, Policy>>(device_, std::move(primitives), policy, options);
        geometry_->attach(scene_);
        rtcCommitScene(scene_);
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (const RTCError e = rtcGetDeviceError(device_); e != RTC_ERROR_NONE) {
            release();
            throw std::runtime_error("rayq::embree: building the scene failed (Embree error " + std::to_string(int(e)) + ")");
        }
    }
    ~Scene() { release(); }
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    // The closest hit, exactly as rayq's scalar loop over every primitive finds it (lowest primID
    // among equal t). Rays Embree cannot take (tmin < 0, a float copy that overflows) are answered
    // by that loop itself: correct, without culling.
    std::optional<EmbreeHit<T>> intersect(const Ray<T>& ray, HitFields fields = HitFields::all) const
    {
        std::optional<EmbreeHit<T>> out;  // every return names it (NRVO): the record is written in place
        if (!usable(ray)) return out;
        QueryContext<T> ctx(ray);
        const std::optional<float> tfar = trace(ctx);
        if (!tfar) {
            out = brute_force(ray, fields);
            return out;
        }
        if (!ctx.found()) return out;
        // From the crossing the callback kept (the record is built once, for the winner).
        out.emplace(EmbreeHit<T>{Hit<T>{}, ctx.geomID, ctx.primID, *tfar});
        if (!geometry_->write_hit_record(ctx, fields, out->hit)) out.reset();  // unreachable: the winner's first crossing is in the window
        return out;
    }

    // The closest hit without rayq's hit record (no normal, no certified bound): t and which
    // primitive, like rayq::nearest for rayq::Scene.
    std::optional<EmbreeRef<T>> nearest(const Ray<T>& ray) const
    {
        if (!usable(ray)) return std::nullopt;
        QueryContext<T> ctx(ray);
        const std::optional<float> tfar = trace(ctx);
        if (!tfar) {
            const std::optional<EmbreeHit<T>> h = brute_force(ray, HitFields::all);  // the t intersect() gives
            if (!h) return std::nullopt;
            return EmbreeRef<T>{h->hit.t, h->geomID, h->primID, h->tfar};
        }
        if (!ctx.found()) return std::nullopt;
        return EmbreeRef<T>{ctx.t, ctx.geomID, ctx.primID, *tfar};
    }

    bool occluded(const Ray<T>& ray) const
    {
        if (!usable(ray)) return false;
        QueryContext<T> ctx(ray);
        std::optional<RTCRayHit> rh = ctx.embree_ray();
        if (!rh) {
            for (const Prim& p : geometry_->primitives())
                if (::rayq::occluded(geometry_->policy(), ray, p)) return true;
            return false;
        }
        rtcOccluded1(scene_, ctx.context(), &rh->ray);
        return ctx.found();
    }

    double build_seconds() const { return build_seconds_; }
    RTCScene handle() const { return scene_; }
    RTCDevice device() const { return device_; }
    const UserGeometry<Prim, Policy>& geometry() const { return *geometry_; }

private:
    // Traces ctx's query through Embree (the callbacks fill ctx): Embree's final tfar, or nullopt
    // for a ray Embree cannot take (QueryContext::embree_ray).
    std::optional<float> trace(QueryContext<T>& ctx) const
    {
        std::optional<RTCRayHit> rh = ctx.embree_ray();
        if (!rh) return std::nullopt;
        rtcIntersect1(scene_, ctx.context(), &*rh);
        return rh->ray.tfar;
    }

    std::optional<EmbreeHit<T>> brute_force(const Ray<T>& ray, HitFields fields) const
    {
        std::optional<EmbreeHit<T>> best;
        const auto& prims = geometry_->primitives();
        for (std::size_t i = 0; i < prims.size(); ++i)
            if (auto h = ::rayq::intersect(geometry_->policy(), ray, prims[i], fields); h && (!best || h->t < best->hit.t))
                best = EmbreeHit<T>{*h, 0u, static_cast<unsigned>(i), detail::to_tfar(h->t)};
        return best;
    }

    void release()
    {
        geometry_.reset();
        if (scene_) rtcReleaseScene(scene_), scene_ = nullptr;
        if (device_) rtcReleaseDevice(device_), device_ = nullptr;
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::unique_ptr<UserGeometry<Prim, Policy>> geometry_;
    double build_seconds_ = 0;
};

}  // namespace rayq::embree
