// Texels of the slices' data textures (render/slices.py). Normals are stored turned up and keep
// the length the mip averaging gave them (shorter where blades disagree): they are not
// normalised here, so the lambert term is the average one.
vec3 vertical_normal(vec4 data) { return data.rgb * 2.0 - 1.0; }

vec3 top_normal(vec4 data) {
    vec2 a = data.rg * 2.0 - 1.0;
    return vec3(a.x, sqrt(max(1.0 - dot(a, a), 0.0)), a.y);
}
