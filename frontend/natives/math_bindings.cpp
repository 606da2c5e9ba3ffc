// Binds the Math bundle's `fn` and `operator` declarations (bundles/Math) to the Eigen implementations in
// math_rotation, math_matrix and math_scalar. Each binding only converts between OpenPLX values and Eigen.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>

#include "frontend/evaluation/evaluator.h"
#include "frontend/evaluation/value_format.h"
#include "frontend/natives/builtin_natives.h"
#include "frontend/natives/math_matrix.h"
#include "frontend/natives/math_rotation.h"
#include "frontend/natives/math_scalar.h"

namespace openplx::natives {
namespace {

using frontend::NativeCall;
using frontend::NativeRegistry;
using frontend::Value;
using Args = std::span<const Value>;
using V3 = Eigen::Vector3d;
using Q = Eigen::Quaterniond;

V3 vec3(NativeCall& c, const Value& v) {
  auto f = c.fields(v, {"x", "y", "z"});
  return {f[0], f[1], f[2]};
}
Eigen::Vector2d vec2(NativeCall& c, const Value& v) {
  auto f = c.fields(v, {"x", "y"});
  return {f[0], f[1]};
}
Q quat(NativeCall& c, const Value& v) {
  auto f = c.fields(v, {"x", "y", "z", "w"});
  return quat_from_xyzw(f[0], f[1], f[2], f[3]);
}
Value make_vec3(NativeCall& c, const V3& v) {
  return c.make("Math.Vec3", {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}});
}
Value make_vec2(NativeCall& c, const Eigen::Vector2d& v) {
  return c.make("Math.Vec2", {{"x", v.x()}, {"y", v.y()}});
}
Value make_quat(NativeCall& c, const Q& q) {
  auto xyzw = quat_to_xyzw(q);
  return c.make("Math.Quat", {{"x", xyzw[0]}, {"y", xyzw[1]}, {"z", xyzw[2]}, {"w", xyzw[3]}});
}
Affine affine(NativeCall& c, const Value& v) {
  return {vec3(c, c.object(v, "position")), quat(c, c.object(v, "rotation"))};
}
Value make_affine(NativeCall& c, const Affine& a) {
  return c.make_with("Math.AffineTransform",
                     {{"position", make_vec3(c, a.position)}, {"rotation", make_quat(c, a.rotation)}});
}
Value real(double v) {
  return Value::of_real(v);
}

template <int N>
Eigen::Matrix<double, N, N> matrix(NativeCall& c, const Value& v) {
  Eigen::Matrix<double, N, N> m;
  for (int r = 0; r < N; ++r) {
    for (int col = 0; col < N; ++col) {
      const std::string name = "e" + std::to_string(r) + std::to_string(col);
      Value e = c.object(v, name);
      m(r, col) = e.as_real();
    }
  }
  return m;
}
template <int N>
Value make_matrix(NativeCall& c, const Eigen::Matrix<double, N, N>& m) {
  Value out = c.make(N == 3 ? "Math.Matrix3x3" : "Math.Matrix4x4", {});
  if (out.is_error()) return out;
  for (int r = 0; r < N; ++r) {
    for (int col = 0; col < N; ++col) {
      c.evaluator().preset(out.object, "e" + std::to_string(r) + std::to_string(col), real(m(r, col)));
    }
  }
  return out;
}
template <typename M>
Value matrix_or_fail(NativeCall& c, const std::optional<M>& m, const char* what) {
  if (!m)
    return c.fail(std::string(what) + ": every row or column needs exactly as many values as the matrix has");
  return make_matrix<M::RowsAtCompileTime>(c, *m);
}

void add_vectors(NativeRegistry& r) {
  r.add("Math.Vec3.X_AXIS", [](NativeCall& c, Args) { return make_vec3(c, V3::UnitX()); });
  r.add("Math.Vec3.Y_AXIS", [](NativeCall& c, Args) { return make_vec3(c, V3::UnitY()); });
  r.add("Math.Vec3.Z_AXIS", [](NativeCall& c, Args) { return make_vec3(c, V3::UnitZ()); });
  r.add("Math.Vec3.from_xyz", [](NativeCall& c, Args a) {
    return make_vec3(c, {a[0].as_real(), a[1].as_real(), a[2].as_real()});
  });
  r.add("Math.Vec3.fromXYZ", *r.find("Math.Vec3.from_xyz"));
  r.add("Math.Vec3.angle_between_vectors", [](NativeCall& c, Args a) {
    return real(angle_between_vectors(vec3(c, a[0]), vec3(c, a[1]), vec3(c, a[2])));
  });
  r.add("Math.Vec3.length", [](NativeCall& c, Args a) { return real(vec3(c, a[0]).norm()); });
  r.add("Math.Vec3.normal", [](NativeCall& c, Args a) {
    V3 v = vec3(c, a[0]);
    if (v.norm() == 0.0) return c.fail("normal() of a zero vector");
    return make_vec3(c, v.normalized());
  });
  r.add("Math.Vec3.dot", [](NativeCall& c, Args a) { return real(vec3(c, a[0]).dot(vec3(c, a[1]))); });
  r.add("Math.Vec3.cross",
        [](NativeCall& c, Args a) { return make_vec3(c, vec3(c, a[0]).cross(vec3(c, a[1]))); });
  r.add("Math.Vec3.get_orthogonal_unit_vector",
        [](NativeCall& c, Args a) { return make_vec3(c, orthogonal_unit_vector(vec3(c, a[0]))); });
  r.add("operator+(Math.Vec3,Math.Vec3)",
        [](NativeCall& c, Args a) { return make_vec3(c, vec3(c, a[0]) + vec3(c, a[1])); });
  r.add("operator-(Math.Vec3,Math.Vec3)",
        [](NativeCall& c, Args a) { return make_vec3(c, vec3(c, a[0]) - vec3(c, a[1])); });
  r.add("operator*(Real,Math.Vec3)",
        [](NativeCall& c, Args a) { return make_vec3(c, a[0].as_real() * vec3(c, a[1])); });
  r.add("operator*(Math.Vec3,Real)",
        [](NativeCall& c, Args a) { return make_vec3(c, vec3(c, a[0]) * a[1].as_real()); });
  r.add("operator*(Math.Vec3,Math.Vec3)",
        [](NativeCall& c, Args a) { return real(vec3(c, a[0]).dot(vec3(c, a[1]))); });
  r.add("operator/(Math.Vec3,Real)",
        [](NativeCall& c, Args a) { return make_vec3(c, vec3(c, a[0]) / a[1].as_real()); });
  r.add("operator-(Math.Vec3)", [](NativeCall& c, Args a) { return make_vec3(c, -vec3(c, a[0])); });

  r.add("Math.Vec2.X_AXIS", [](NativeCall& c, Args) { return make_vec2(c, Eigen::Vector2d::UnitX()); });
  r.add("Math.Vec2.Y_AXIS", [](NativeCall& c, Args) { return make_vec2(c, Eigen::Vector2d::UnitY()); });
  r.add("Math.Vec2.from_xy", [](NativeCall& c, Args a) {
    return make_vec2(c, {a[0].as_real(), a[1].as_real()});
  });
  r.add("Math.Vec2.length", [](NativeCall& c, Args a) { return real(vec2(c, a[0]).norm()); });
  r.add("Math.Vec2.normal", [](NativeCall& c, Args a) {
    Eigen::Vector2d v = vec2(c, a[0]);
    if (v.norm() == 0.0) return c.fail("normal() of a zero vector");
    return make_vec2(c, v.normalized());
  });
  r.add("Math.Vec2.dot", [](NativeCall& c, Args a) { return real(vec2(c, a[0]).dot(vec2(c, a[1]))); });
  r.add("operator+(Math.Vec2,Math.Vec2)",
        [](NativeCall& c, Args a) { return make_vec2(c, vec2(c, a[0]) + vec2(c, a[1])); });
  r.add("operator-(Math.Vec2,Math.Vec2)",
        [](NativeCall& c, Args a) { return make_vec2(c, vec2(c, a[0]) - vec2(c, a[1])); });
  r.add("operator*(Real,Math.Vec2)",
        [](NativeCall& c, Args a) { return make_vec2(c, a[0].as_real() * vec2(c, a[1])); });
  r.add("operator*(Math.Vec2,Real)",
        [](NativeCall& c, Args a) { return make_vec2(c, vec2(c, a[0]) * a[1].as_real()); });
  r.add("operator*(Math.Vec2,Math.Vec2)",
        [](NativeCall& c, Args a) { return real(vec2(c, a[0]).dot(vec2(c, a[1]))); });
  r.add("operator/(Math.Vec2,Real)",
        [](NativeCall& c, Args a) { return make_vec2(c, vec2(c, a[0]) / a[1].as_real()); });
  r.add("operator-(Math.Vec2)", [](NativeCall& c, Args a) { return make_vec2(c, -vec2(c, a[0])); });
}

void add_quaternions(NativeRegistry& r) {
  r.add("Math.Quat.rotate",
        [](NativeCall& c, Args a) { return make_vec3(c, quat_rotate(quat(c, a[0]), vec3(c, a[1]))); });
  r.add("Math.Quat.conj", [](NativeCall& c, Args a) { return make_quat(c, quat_conj(quat(c, a[0]))); });
  r.add("Math.Quat.inverse", [](NativeCall& c, Args a) { return make_quat(c, quat_inverse(quat(c, a[0]))); });
  r.add("Math.Quat.angle_axis", [](NativeCall& c, Args a) {
    const double angle = a[0].as_real();
    const V3 axis = vec3(c, a[1]);
    // A turn about no axis is no rotation we could pick; taking the identity would be silently wrong. A zero
    // angle is the identity whatever the axis.
    if (angle != 0.0 && axis.cwiseAbs().maxCoeff() == 0.0) {
      c.evaluator().sink().report(frontend::DiagCode::InvalidValue, c.where(),
                                  "`Math.Quat.angle_axis` turns " + frontend::format_real(angle) +
                                      " rad about the zero vector; an axis has a length");
      return Value::error();
    }
    return make_quat(c, quat_angle_axis(angle, axis));
  });
  r.add("Math.Quat.from_to",
        [](NativeCall& c, Args a) { return make_quat(c, quat_from_to(vec3(c, a[0]), vec3(c, a[1]))); });
  r.add("Math.Quat.normal", [](NativeCall& c, Args a) { return make_quat(c, quat_normal(quat(c, a[0]))); });
  r.add("Math.Quat.from_xyzw", [](NativeCall& c, Args a) {
    return make_quat(c, quat_from_xyzw(a[0].as_real(), a[1].as_real(), a[2].as_real(), a[3].as_real()));
  });
  r.add("Math.Quat.angleAxis", *r.find("Math.Quat.angle_axis"));
  r.add("Math.Quat.fromTo", *r.find("Math.Quat.from_to"));
  r.add("Math.Quat.fromXYZW", *r.find("Math.Quat.from_xyzw"));
  for (std::string_view convention : euler_conventions()) {
    const std::string name(convention);
    r.add("Math.Quat.from_euler_angles_" + name, [name](NativeCall& c, Args a) {
      return make_quat(c, *quat_from_euler(name, a[0].as_real(), a[1].as_real(), a[2].as_real()));
    });
  }
  r.add("Math.Quat.from_euler_angles", *r.find("Math.Quat.from_euler_angles_xyzs"));
  r.add("operator*(Math.Quat,Math.Quat)",
        [](NativeCall& c, Args a) { return make_quat(c, quat(c, a[0]) * quat(c, a[1])); });
}

void add_transforms(NativeRegistry& r) {
  r.add("Math.AffineTransform.create", [](NativeCall& c, Args) { return make_affine(c, Affine{}); });
  r.add("Math.AffineTransform.from", [](NativeCall& c, Args a) {
    return make_affine(c, Affine{vec3(c, a[0]), quat(c, a[1])});
  });
  r.add("Math.AffineTransform.from_axes", [](NativeCall& c, Args a) {
    std::optional<Affine> t = affine_from_axes(vec3(c, a[0]), vec3(c, a[1]), vec3(c, a[2]));
    if (!t) return c.fail("from_axes needs a non-zero new_Z and a new_X that is not parallel to it");
    return make_affine(c, *t);
  });
  r.add("Math.AffineTransform.inverse_of", [](NativeCall& c, Args a) {
    return make_affine(c, affine_inverse_of(vec3(c, a[0]), quat(c, a[1])));
  });
  r.add("Math.AffineTransform.inverse",
        [](NativeCall& c, Args a) { return make_affine(c, affine_inverse(affine(c, a[0]))); });
  r.add("Math.AffineTransform.transform_vec3_point", [](NativeCall& c, Args a) {
    return make_vec3(c, affine_transform_point(affine(c, a[0]), vec3(c, a[1])));
  });
  r.add("Math.AffineTransform.transform_vec3_vector", [](NativeCall& c, Args a) {
    return make_vec3(c, affine_transform_vector(affine(c, a[0]), vec3(c, a[1])));
  });
  r.add("operator*(Math.AffineTransform,Math.AffineTransform)", [](NativeCall& c, Args a) {
    return make_affine(c, affine_compose(affine(c, a[0]), affine(c, a[1])));
  });
}

void add_matrices(NativeRegistry& r) {
  r.add("Math.Matrix3x3.from_row_major", [](NativeCall& c, Args a) {
    std::vector<double> v;
    for (const Value& x : a) v.push_back(x.as_real());
    return matrix_or_fail(c, matrix3_from_row_major(v), "from_row_major");
  });
  r.add("Math.Matrix3x3.from_rows", [](NativeCall& c, Args a) {
    return matrix_or_fail(c, matrix3_from_rows(c.reals(a[0]), c.reals(a[1]), c.reals(a[2])), "from_rows");
  });
  r.add("Math.Matrix3x3.from_columns", [](NativeCall& c, Args a) {
    return matrix_or_fail(c, matrix3_from_columns(c.reals(a[0]), c.reals(a[1]), c.reals(a[2])),
                          "from_columns");
  });
  r.add("Math.Matrix3x3.diag", [](NativeCall& c, Args a) {
    return make_matrix<3>(c, matrix3_diag(a[0].as_real(), a[1].as_real(), a[2].as_real()));
  });
  r.add("operator+(Math.Matrix3x3,Math.Matrix3x3)",
        [](NativeCall& c, Args a) { return make_matrix<3>(c, matrix<3>(c, a[0]) + matrix<3>(c, a[1])); });
  r.add("operator-(Math.Matrix3x3,Math.Matrix3x3)",
        [](NativeCall& c, Args a) { return make_matrix<3>(c, matrix<3>(c, a[0]) - matrix<3>(c, a[1])); });
  r.add("operator*(Math.Matrix3x3,Math.Matrix3x3)",
        [](NativeCall& c, Args a) { return make_matrix<3>(c, matrix<3>(c, a[0]) * matrix<3>(c, a[1])); });
  r.add("operator*(Math.Matrix3x3,Math.Vec3)",
        [](NativeCall& c, Args a) { return make_vec3(c, matrix<3>(c, a[0]) * vec3(c, a[1])); });

  r.add("Math.Matrix4x4.from_row_major", [](NativeCall& c, Args a) {
    std::vector<double> v;
    for (const Value& x : a) v.push_back(x.as_real());
    return matrix_or_fail(c, matrix4_from_row_major(v), "from_row_major");
  });
  r.add("Math.Matrix4x4.from_rows", [](NativeCall& c, Args a) {
    return matrix_or_fail(c, matrix4_from_rows(c.reals(a[0]), c.reals(a[1]), c.reals(a[2]), c.reals(a[3])),
                          "from_rows");
  });
  r.add("Math.Matrix4x4.from_columns", [](NativeCall& c, Args a) {
    return matrix_or_fail(c, matrix4_from_columns(c.reals(a[0]), c.reals(a[1]), c.reals(a[2]), c.reals(a[3])),
                          "from_columns");
  });
  r.add("Math.Matrix4x4.from_vec3_quat", [](NativeCall& c, Args a) {
    return make_matrix<4>(c, matrix4_from_vec3_quat(vec3(c, a[0]), quat(c, a[1])));
  });
  r.add("Math.Matrix4x4.transpose", [](NativeCall& c, Args a) {
    Eigen::Matrix4d m = matrix<4>(c, a[0]).transpose();
    return make_matrix<4>(c, m);
  });
  r.add("Math.Matrix4x4.copy", [](NativeCall& c, Args a) { return make_matrix<4>(c, matrix<4>(c, a[0])); });
  r.add("Math.Matrix4x4.get_affine_translation",
        [](NativeCall& c, Args a) { return make_vec3(c, matrix4_affine_translation(matrix<4>(c, a[0]))); });
  r.add("Math.Matrix4x4.get_affine_rotation",
        [](NativeCall& c, Args a) { return make_quat(c, matrix4_affine_rotation(matrix<4>(c, a[0]))); });
  r.add("operator+(Math.Matrix4x4,Math.Matrix4x4)",
        [](NativeCall& c, Args a) { return make_matrix<4>(c, matrix<4>(c, a[0]) + matrix<4>(c, a[1])); });
  r.add("operator-(Math.Matrix4x4,Math.Matrix4x4)",
        [](NativeCall& c, Args a) { return make_matrix<4>(c, matrix<4>(c, a[0]) - matrix<4>(c, a[1])); });
  r.add("operator*(Math.Matrix4x4,Math.Matrix4x4)",
        [](NativeCall& c, Args a) { return make_matrix<4>(c, matrix<4>(c, a[0]) * matrix<4>(c, a[1])); });

  r.add("Math.Line.from_points", [](NativeCall& c, Args a) {
    return c.make_with("Math.Line",
                       {{"start", make_vec3(c, vec3(c, a[0]))}, {"end", make_vec3(c, vec3(c, a[1]))}});
  });
  r.add("Math.Line.length", [](NativeCall& c, Args a) {
    return real(line_length(vec3(c, c.object(a[0], "start")), vec3(c, c.object(a[0], "end"))));
  });
}

void add_functions(NativeRegistry& r) {
  using Unary = double (*)(double);
  const std::array<std::pair<const char*, Unary>, 9> unary = {{{"sin", &natives::sin},
                                                               {"cos", &natives::cos},
                                                               {"tan", &natives::tan},
                                                               {"arcsin", &natives::arcsin},
                                                               {"arccos", &natives::arccos},
                                                               {"arctan", &natives::arctan},
                                                               {"sqrt", &natives::sqrt},
                                                               {"rad_to_deg", &natives::rad_to_deg},
                                                               {"deg_to_rad", &natives::deg_to_rad}}};
  for (const auto& entry : unary) {
    Unary fn = entry.second;  // a copy: clang 14 cannot capture structured bindings
    r.add(std::string("Math.Functions.") + entry.first,
          [fn](NativeCall&, Args a) { return real(fn(a[0].as_real())); });
  }
  using Reduce = double (*)(std::span<const double>);
  const std::array<std::pair<const char*, Reduce>, 6> reduce = {{{"mean", &natives::mean},
                                                                 {"median", &natives::median},
                                                                 {"harmonic_mean", &natives::harmonic_mean},
                                                                 {"min", &natives::min},
                                                                 {"max", &natives::max},
                                                                 {"sum", &natives::sum}}};
  for (const auto& entry : reduce) {
    Reduce fn = entry.second;
    r.add(std::string("Math.Functions.") + entry.first,
          [fn](NativeCall& c, Args a) { return real(fn(c.reals(a[0]))); });
  }
  r.add("Math.Functions.ceil", [](NativeCall&, Args a) { return real(std::ceil(a[0].as_real())); });
  r.add("Math.Functions.floor", [](NativeCall&, Args a) { return real(std::floor(a[0].as_real())); });
  r.add("Math.Functions.arctan2",
        [](NativeCall&, Args a) { return real(arctan2(a[0].as_real(), a[1].as_real())); });
  r.add("Math.Functions.pow",
        [](NativeCall&, Args a) { return real(natives::pow(a[0].as_real(), a[1].as_real())); });
  r.add("Math.Functions.equals_approx",
        [](NativeCall&, Args a) { return Value::of_bool(equals_approx(a[0].as_real(), a[1].as_real())); });
  r.add("Math.Functions.inf", [](NativeCall&, Args) { return real(inf()); });
  r.add("Math.Functions.neg_inf", [](NativeCall&, Args) { return real(neg_inf()); });
}

}  // namespace

void register_math_natives(NativeRegistry& registry) {
  add_vectors(registry);
  add_quaternions(registry);
  add_transforms(registry);
  add_matrices(registry);
  add_functions(registry);
}

}  // namespace openplx::natives
