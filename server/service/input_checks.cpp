#include "service/input_checks.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "service/errors.h"

namespace strata::service {
namespace {

void check_finite_in(float v, const std::string& field, float max_abs) {
  if (!std::isfinite(v)) fail_invalid(field + " = " + format_float(v) + " is not finite");
  if (std::fabs(v) > max_abs)
    fail_invalid(field + " = " + format_float(v) + " is outside [-" + format_float(max_abs) + ", " + format_float(max_abs) + "]");
}

}  // namespace

std::string format_float(float v) {
  // The shortest %g form that reads back as the same float.
  char buf[48];
  for (int precision = 6; precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, double(v));
    if (!std::isfinite(v) || std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

glm::vec3 check_vec3(const v1::Vec3& v, const std::string& field, float max_abs) {
  check_finite_in(v.x(), field + ".x", max_abs);
  check_finite_in(v.y(), field + ".y", max_abs);
  check_finite_in(v.z(), field + ".z", max_abs);
  return {v.x(), v.y(), v.z()};
}

glm::quat check_quaternion(const v1::Quaternion& q, const std::string& field) {
  check_finite_in(q.w(), field + ".w", 2.0f);
  check_finite_in(q.x(), field + ".x", 2.0f);
  check_finite_in(q.y(), field + ".y", 2.0f);
  check_finite_in(q.z(), field + ".z", 2.0f);
  glm::quat r(q.w(), q.x(), q.y(), q.z());
  float norm = glm::length(r);
  if (std::fabs(norm - 1.0f) > 1e-3f)
    fail_invalid(field + " has norm " + format_float(norm) + "; a rotation must be a unit quaternion (norm within 1e-3 of 1)");
  return glm::normalize(r);
}

scene::Camera check_camera(const v1::Camera& c, const std::string& field) {
  if (!c.has_position()) fail_invalid(field + ".position is required");
  if (!c.has_orientation()) fail_invalid(field + ".orientation is required");
  scene::Camera cam;
  cam.position = check_vec3(c.position(), field + ".position", k_max_coordinate);
  cam.orientation = check_quaternion(c.orientation(), field + ".orientation");
  const float fov = c.vertical_fov();
  if (!std::isfinite(fov) || fov <= 0.0f || fov >= std::numbers::pi_v<float>)
    fail_invalid(field + ".vertical_fov = " + format_float(fov) + " rad is outside (0, pi)");
  cam.yfov = fov;
  const float aperture = c.aperture();
  if (!std::isfinite(aperture) || aperture < 0.0f || aperture > k_max_aperture)
    fail_invalid(field + ".aperture = " + format_float(aperture) + " m is outside [0, " + format_float(k_max_aperture) + "]");
  cam.aperture = aperture;
  const float focus = c.focus_distance();
  if (!std::isfinite(focus) || focus < 0.0f || focus > k_max_coordinate)
    fail_invalid(field + ".focus_distance = " + format_float(focus) + " m is outside [0, " + format_float(k_max_coordinate) + "]");
  if (aperture > 0.0f && focus <= 0.0f)
    fail_invalid(field + ".focus_distance = " + format_float(focus) + " must be > 0 when " + field + ".aperture > 0");
  cam.focus_distance = focus > 0.0f ? focus : 1.0f;
  const float shutter = c.shutter();
  if (!std::isfinite(shutter) || shutter < 0.0f || shutter > 1.0f)
    fail_invalid(field + ".shutter = " + format_float(shutter) + " is outside [0, 1] (fraction of the frame interval)");
  cam.shutter = shutter;
  return cam;
}

glm::mat4 check_transform(const v1::InstanceTransform& t, const std::string& field) {
  if (!t.has_translation()) fail_invalid(field + ".translation is required");
  if (!t.has_rotation()) fail_invalid(field + ".rotation is required");
  if (!t.has_scale()) fail_invalid(field + ".scale is required");
  glm::vec3 translation = check_vec3(t.translation(), field + ".translation", k_max_coordinate);
  glm::quat rotation = check_quaternion(t.rotation(), field + ".rotation");
  glm::vec3 scale = check_vec3(t.scale(), field + ".scale", k_max_scale);
  for (int i = 0; i < 3; ++i)
    if (std::fabs(scale[i]) < k_min_scale)
      fail_invalid(field + ".scale." + "xyz"[i] + " = " + format_float(scale[i]) + " is smaller in magnitude than " +
                   format_float(k_min_scale) + " (a degenerate transform)");
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

glm::mat4 check_joint_transform(const v1::JointTransform& t, const std::string& field) {
  if (!t.has_translation()) fail_invalid(field + ".translation is required");
  if (!t.has_rotation()) fail_invalid(field + ".rotation is required");
  const glm::vec3 translation = check_vec3(t.translation(), field + ".translation", k_max_coordinate);
  const glm::quat rotation = check_quaternion(t.rotation(), field + ".rotation");
  glm::vec3 scale(1.0f);
  if (t.has_scale()) {
    scale = check_vec3(t.scale(), field + ".scale", k_max_scale);
    for (int i = 0; i < 3; ++i)
      if (std::fabs(scale[i]) < k_min_scale)
        fail_invalid(field + ".scale." + "xyz"[i] + " = " + format_float(scale[i]) + " is smaller in magnitude than " +
                     format_float(k_min_scale) + " (a degenerate transform)");
  }
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

glm::mat4 check_light_transform(const v1::LightTransform& t, const std::string& field) {
  if (!t.has_translation()) fail_invalid(field + ".translation is required");
  if (!t.has_rotation()) fail_invalid(field + ".rotation is required");
  const glm::vec3 translation = check_vec3(t.translation(), field + ".translation", k_max_coordinate);
  const glm::quat rotation = check_quaternion(t.rotation(), field + ".rotation");
  return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation);
}

void check_resolution(const v1::Resolution& r, const ServiceLimits& limits, const std::string& field) {
  const std::string max = std::to_string(limits.max_dimension);
  if (r.width() < 1 || r.width() > limits.max_dimension)
    fail_invalid(field + ".width = " + std::to_string(r.width()) + " is outside [1, " + max + "] (max_dimension)");
  if (r.height() < 1 || r.height() > limits.max_dimension)
    fail_invalid(field + ".height = " + std::to_string(r.height()) + " is outside [1, " + max + "] (max_dimension)");
  const uint64_t pixels = uint64_t(r.width()) * r.height();
  if (pixels > limits.max_pixels)
    fail_invalid(field + ".width * " + field + ".height = " + std::to_string(pixels) + " exceeds max_pixels = " +
                 std::to_string(limits.max_pixels));
}

std::vector<v1::ImageEncoding> check_encodings(const google::protobuf::RepeatedField<int>& requested, const std::string& field) {
  if (requested.empty()) return {v1::IMAGE_ENCODING_EXR_HALF};
  std::vector<v1::ImageEncoding> out;
  for (int i = 0; i < requested.size(); ++i) {
    const int e = requested[i];
    const std::string at = field + "[" + std::to_string(i) + "]";
    if (e == v1::IMAGE_ENCODING_UNSPECIFIED || !v1::ImageEncoding_IsValid(e))
      fail_invalid(at + " = " + std::to_string(e) + " is not an image encoding (EXR_HALF = 1, RAW_RGBA16F = 2, PNG_PREVIEW = 3, DOMAIN_MAP = 4)");
    const auto enc = static_cast<v1::ImageEncoding>(e);
    for (auto seen : out)
      if (seen == enc) fail_invalid(at + " = " + encoding_name(enc) + " is requested twice");
    out.push_back(enc);
  }
  return out;
}

std::string encoding_name(v1::ImageEncoding e) {
  switch (e) {
    case v1::IMAGE_ENCODING_EXR_HALF: return "EXR_HALF";
    case v1::IMAGE_ENCODING_RAW_RGBA16F: return "RAW_RGBA16F";
    case v1::IMAGE_ENCODING_PNG_PREVIEW: return "PNG_PREVIEW";
    case v1::IMAGE_ENCODING_DOMAIN_MAP: return "DOMAIN_MAP";
    default: return "UNSPECIFIED";
  }
}

}  // namespace strata::service
