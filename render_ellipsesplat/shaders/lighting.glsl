// Blinn-Phong with one directional light, two-sided: the same in every mode so that splats,
// points and reference meshes are comparable pixel for pixel.
uniform vec3 towardsLight;
uniform vec3 lightAmbient;
uniform vec3 lightDiffuse;
uniform vec3 lightSpecular;
uniform float shininess;

vec3 shade(vec3 albedo, vec3 normal, vec3 towardsEye)
{
    vec3 n = dot(normal, normal) > 0.0 ? normalize(normal) : towardsEye;
    if (dot(n, towardsEye) < 0.0)
        n = -n;
    vec3 l = normalize(towardsLight);
    float diffuse = max(dot(n, l), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(l + towardsEye)), 0.0), shininess) : 0.0;
    return albedo * (lightAmbient + lightDiffuse * diffuse) + lightSpecular * specular;
}
