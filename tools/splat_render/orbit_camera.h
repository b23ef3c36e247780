#pragma once
// A perspective camera aimed at a bounding sphere from a direction given by azimuth and
// elevation or by a vector; matrices are column-major, as OpenGL and the renderer take them.

namespace splat {

struct Camera
{
    float modelView[16];
    float projection[16];
    float nearPlane, farPlane;
};

struct CameraSetup
{
    float center[3] = {0, 0, 0}; // of the bounding sphere to frame
    float radius = 1.0f;
    float viewDirection[3] = {0, 0, -1}; // from the camera towards the centre
    float fovYDegrees = 30.0f;
    float aspect = 1.0f; // width / height
    float zoom = 1.0f;   // 1: the sphere just fits; 2: twice as large on screen
};

// The view direction for azimuth a (about +Y, 0 = from +Z) and elevation e (above XZ), degrees.
void viewDirectionFromAngles(float azimuthDegrees, float elevationDegrees, float direction[3]);

Camera frameBoundingSphere(const CameraSetup &setup);

// Distance in front of the camera (−z in eye space) of a window depth in [0, 1] (depth range
// 0..1), for any projection.
float eyeDistance(const Camera &camera, float windowDepth);

} // namespace splat
