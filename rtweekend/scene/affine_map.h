#pragma once
// affine_map: the transform nodes a shape sits under, composed, as the scene compiler carries them
// down the world's tree (scene/scene_compiler.h) and the shape kinds apply them to the shapes they
// flatten (scene/shapes/).

#include "../transform.h"
#include "../vec3.h"

#include <cmath>

namespace rt {

// An affine map x -> M x + t, in double: the transform nodes a shape sits under (translate,
// rotate_y, transform, rotate, scale), composed. The compiler applies it to the shapes themselves
// when it can (flattened, they cost nothing more at render time), or makes the subtree an
// instance that keeps it (instance_set.h): see scene_compiler::must_instance.
struct affine_map {
    mat3 m; // M
    vec3 t{0, 0, 0};
    bool identity = true;

    vec3 vector(const vec3& v) const { return identity ? v : m * v; }
    point3 point(const point3& p) const { return identity ? p : m * p + t; }
    // A normal through the map: by the inverse transpose (normals are gradients), unnormalised.
    vec3 normal(const vec3& n) const { return identity ? n : m.inverse().transpose() * n; }
    // This map after `inner` (inner applied first).
    affine_map then(const affine_map& inner) const {
        if (inner.identity) return *this;
        if (identity) return inner;
        affine_map r;
        r.m = m * inner.m;
        r.t = vector(inner.t) + t;
        r.identity = false;
        return r;
    }
    static affine_map linear(const mat3& linear, const vec3& offset) {
        affine_map r;
        r.m = linear;
        r.t = offset;
        r.identity = false;
        return r;
    }
    static affine_map translation(const vec3& offset) { return linear(mat3(), offset); }
    // rotate_y's object-to-world rotation: x' = cos x + sin z, z' = -sin x + cos z.
    static affine_map rotation_y(double sin_theta, double cos_theta) {
        return linear(mat3(vec3(cos_theta, 0, sin_theta), vec3(0, 1, 0), vec3(-sin_theta, 0, cos_theta)), vec3(0, 0, 0));
    }
    // s when M is s times a rotation (M^T M = s^2 I and det M > 0), so that a sphere of radius r
    // maps to the sphere of radius s r; 0 when it is not (a sphere would become an ellipsoid).
    double sphere_scale() const {
        if (identity) return 1;
        const mat3 mtm = m.transpose() * m;
        const double s2 = (mtm(0, 0) + mtm(1, 1) + mtm(2, 2)) / 3;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (!(std::fabs(mtm(i, j) - (i == j ? s2 : 0.0)) <= 1e-12 * s2)) return 0;
        return m.determinant() > 0 ? std::sqrt(s2) : 0;
    }
};

} // namespace rt
