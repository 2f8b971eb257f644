#pragma once
// Checks of the values clients send. Each failure is INVALID_ARGUMENT naming the field (as a path
// such as "camera.position.x"), the value and the allowed range.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/scene.h"
#include "service/config.h"
#include "strata/v1/render.pb.h"

namespace strata::service {

namespace v1 = ::strata::v1;

constexpr float k_max_coordinate = 1e8f;  // metres from the origin
constexpr float k_min_scale = 1e-6f, k_max_scale = 1e6f;
constexpr float k_max_morph_weight = 16.0f;  // a morph target weight's magnitude (FrameInput.morph_weights)
constexpr float k_max_aperture = 1e3f;    // metres

std::string format_float(float v);

glm::vec3 check_vec3(const v1::Vec3& v, const std::string& field, float max_abs);
// Unit quaternion within 1e-3; returned normalised.
glm::quat check_quaternion(const v1::Quaternion& q, const std::string& field);
// Light to world from a LightTransform (translation and rotation required).
glm::mat4 check_light_transform(const v1::LightTransform& t, const std::string& field);
// A joint's joint to world (translation and rotation required, scale optional).
glm::mat4 check_joint_transform(const v1::JointTransform& t, const std::string& field);

// Position, orientation, field of view, thin lens and shutter (motion blur, RS-main 4.4).
scene::Camera check_camera(const v1::Camera& c, const std::string& field);

// translate * rotate * scale; every part is required.
glm::mat4 check_transform(const v1::InstanceTransform& t, const std::string& field);

void check_resolution(const v1::Resolution& r, const ServiceLimits& limits, const std::string& field);

// Empty `requested` means [EXR_HALF]. Each encoding at most once.
std::vector<v1::ImageEncoding> check_encodings(const google::protobuf::RepeatedField<int>& requested,
                                               const std::string& field);

std::string encoding_name(v1::ImageEncoding e);

}  // namespace strata::service
