#include "renderer/camera/auto_frame.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pelage::renderer {
namespace {

constexpr float deg = 3.14159265358979f / 180;

}  // namespace

Vec3f long_horizontal_axis(const std::vector<Vec3f> &points, Vec3f up) {
    Vec3f lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (const Vec3f &p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    const Vec3f center = (lo + hi) * 0.5f;
    const Frame f = Frame::from_z(up);
    double sxx = 0, sxy = 0, syy = 0;
    for (const Vec3f &p : points) {
        const Vec3f l = f.to_local(p - center);
        sxx += double(l.x) * l.x;
        sxy += double(l.x) * l.y;
        syy += double(l.y) * l.y;
    }
    // The eigenvector of [[sxx, sxy], [sxy, syy]] with the larger eigenvalue.
    const double angle = 0.5 * std::atan2(2 * sxy, sxx - syy);
    return normalize(f.s * float(std::cos(angle)) + f.t * float(std::sin(angle)));
}

Framing frame_points(const std::vector<Vec3f> &points, const FramingRequest &rq) {
    if (points.empty()) throw std::invalid_argument("no points to frame");
    if (!(length(rq.up) > 0)) throw std::invalid_argument("zero up direction");
    const Vec3f up = normalize(rq.up);
    Vec3f lo{1e30f, 1e30f, 1e30f}, hi{-1e30f, -1e30f, -1e30f};
    for (const Vec3f &p : points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw std::invalid_argument("a point is not finite");
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    Framing fr;
    fr.center = (lo + hi) * 0.5f;
    fr.ground = 1e30f;
    for (const Vec3f &p : points) {
        fr.radius = std::max(fr.radius, length(p - fr.center));
        fr.ground = std::min(fr.ground, dot(p, up));
    }
    // A single point (or a speck) still gets a camera at a sensible distance.
    fr.radius = std::max(fr.radius, 1e-6f * std::max(1.0f, length(fr.center)));
    const Vec3f given = rq.long_axis - up * dot(rq.long_axis, up);  // horizontal part
    fr.long_axis =
        length(given) > 0 ? normalize(given) : long_horizontal_axis(points, up);
    fr.side_axis = normalize(cross(up, fr.long_axis));
    if (dot(rq.side_axis, fr.side_axis) < 0) fr.side_axis = -fr.side_axis;

    const float az = rq.azimuth_deg * deg, el = rq.elevation_deg * deg;
    fr.view = normalize((fr.side_axis * std::cos(az) + fr.long_axis * std::sin(az)) *
                            std::cos(el) +
                        up * std::sin(el));
    const Vec3f forward = -fr.view;
    const Vec3f right = normalize(cross(forward, up));
    const Vec3f cam_up = cross(right, forward);
    const float tan_v = std::tan(0.5f * rq.fov_deg * deg), tan_h = tan_v * rq.aspect;
    const float limit = 1 - rq.margin;

    // The nearest camera distance at which every point is inside the shrunk frame: the
    // projections shrink monotonically with the distance, so bisect between a camera at
    // the bounding sphere (too near) and one that fits the whole sphere.

    auto fits = [&](float d, size_t stride) {
        const Vec3f eye = fr.center + fr.view * d;
        for (size_t i = 0; i < points.size(); i += stride) {
            const Vec3f q = points[i] - eye;
            const float z = dot(q, forward);
            if (z <= 0 || std::abs(dot(q, right)) > limit * tan_h * z ||
                std::abs(dot(q, cam_up)) > limit * tan_v * z)
                return false;
        }
        return true;
    };
    const size_t stride = std::max<size_t>(1, points.size() / 20000);
    float near = fr.radius * 1.0001f;
    float far = fr.radius / std::sin(std::atan(limit * std::min(tan_v, tan_h))) * 1.01f;
    for (int i = 0; i < 60 && far - near > 1e-6f * far; ++i) {
        const float mid = 0.5f * (near + far);
        (fits(mid, stride) ? far : near) = mid;
    }
    // A subset of a dense mesh fits at `far`; the camera backs off until all points do.
    while (!fits(far, 1)) far *= 1.01f;

    fr.camera.type = CameraDesc::Type::pinhole;
    fr.camera.position = fr.center + fr.view * far;
    fr.camera.look_at = fr.center;
    fr.camera.up = up;
    fr.camera.fov_deg = rq.fov_deg;
    return fr;
}

}  // namespace pelage::renderer
