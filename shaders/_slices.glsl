// A texel of a slice's data texture (render/slices.py): the normal turned to +axis with only its
// two other components kept, the height above the ground over the patch height, the threshold.
vec3 slice_normal(vec4 data, int axis) {
    vec2 a = data.rg * 2.0 - 1.0;
    float k = sqrt(max(1.0 - dot(a, a), 0.0));
    vec3 n = axis == 0 ? vec3(k, a.x, a.y) : (axis == 1 ? vec3(a.x, k, a.y) : vec3(a.x, a.y, k));
    return normalize(n);
}
