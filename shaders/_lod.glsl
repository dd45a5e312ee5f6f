// Seamless transitions (thesis 5.4, eq. 5.26). lod = (w, side): side 0 is the near
// representation of a transition and keeps blades with threshold / density below w, side 1 the
// far one and keeps the rest; a smoothstep window of half-width u_epsilon blends the crossover.
uniform float u_epsilon;

float lod_opacity(float threshold, float density, vec2 lod) {
    float x = threshold / max(density, 1e-6);
    if (x > 1.0) return 0.0;
    float eps = max(u_epsilon, 1e-4);
    float near = 1.0 - smoothstep(lod.x - eps, lod.x + eps, x);
    return lod.y < 0.5 ? near : 1.0 - near;
}
