#include "orbit_camera.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace splat {
namespace {
const float kPi = 3.14159265358979f;
float radians(float degrees) { return degrees * kPi / 180.0f; }
} // namespace

void viewDirectionFromAngles(float azimuthDegrees, float elevationDegrees, float direction[3])
{
    const float a = radians(azimuthDegrees), e = radians(elevationDegrees);
    // The camera sits at (sin a cos e, sin e, cos a cos e) and looks back at the origin.
    direction[0] = -std::sin(a) * std::cos(e);
    direction[1] = -std::sin(e);
    direction[2] = -std::cos(a) * std::cos(e);
}

Camera frameBoundingSphere(const CameraSetup &setup)
{
    using Eigen::Vector3f;
    const Vector3f center(setup.center);
    const Vector3f forward = Vector3f(setup.viewDirection).normalized();
    // Fit the sphere into the narrower of the two fields of view.
    const float halfFovY = radians(setup.fovYDegrees) / 2.0f;
    const float halfFovX = std::atan(std::tan(halfFovY) * setup.aspect);
    const float distance = setup.radius / std::sin(std::min(halfFovY, halfFovX)) / setup.zoom;
    const Vector3f eye = center - forward * distance;

    const Vector3f worldUp = std::fabs(forward.y()) > 0.99f ? Vector3f(0, 0, -1) : Vector3f(0, 1, 0);
    const Vector3f right = forward.cross(worldUp).normalized();
    const Vector3f up = right.cross(forward);
    Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
    view.block<1, 3>(0, 0) = right.transpose();
    view.block<1, 3>(1, 0) = up.transpose();
    view.block<1, 3>(2, 0) = -forward.transpose();
    view.block<3, 1>(0, 3) = -view.topLeftCorner<3, 3>() * eye;

    Camera camera;
    camera.nearPlane = std::max(distance - 1.5f * setup.radius, 0.01f * distance);
    camera.farPlane = distance + 1.5f * setup.radius;
    const float n = camera.nearPlane, f = camera.farPlane, t = 1.0f / std::tan(halfFovY);
    Eigen::Matrix4f projection = Eigen::Matrix4f::Zero();
    projection(0, 0) = t / setup.aspect;
    projection(1, 1) = t;
    projection(2, 2) = -(f + n) / (f - n);
    projection(2, 3) = -2.0f * f * n / (f - n);
    projection(3, 2) = -1.0f;
    Eigen::Map<Eigen::Matrix4f>(camera.modelView) = view;
    Eigen::Map<Eigen::Matrix4f>(camera.projection) = projection;
    return camera;
}

float eyeDistance(const Camera &camera, float windowDepth)
{
    const Eigen::Vector4f eye =
        Eigen::Map<const Eigen::Matrix4f>(camera.projection).inverse() * Eigen::Vector4f(0, 0, 2 * windowDepth - 1, 1);
    return -eye.z() / eye.w();
}

} // namespace splat
