// Blade segments fewer with distance (core/segments.py): a draw holds the instances binned at
// one level (u_segment_level); within it each blade's leaving vertices slide onto the chord of
// the next level as the instance's continuous level f rises, so no step shows.
uniform float u_segment_scale;   // 0: every row drawn, no sliding
uniform float u_segment_level;   // this draw's level
uniform float u_segment_last;    // the last level (one segment)
uniform float u_subdivisions;    // the patch's rows are 0 ... subdivisions

// How far this draw's leaving vertices have slid at level f: 0 at its level, 1 at the next.
// The next level's chord strays 4^(k + 1 - f) TOLERANCE_PX from the curve (core/segments.py), so
// sliding (4^(f - k) - 1) / 3 of the way keeps the drawn shape within the tolerance throughout
float segment_morph(float f) {
    if (u_segment_scale <= 0.0 || u_segment_level >= u_segment_last) return 0.0;
    return clamp((exp2(2.0 * (f - u_segment_level)) - 1.0) / 3.0, 0.0, 1.0);
}

// The blade's width at this draw's level slid `m` toward the next: each level's strip is
// shorter than the full one (its chords cut the curve's corners), and as much wider, so the
// blade covers what the full strip covers (core/segments.py level_widths)
float segment_width(vec4 widths, float m) {
    float here = u_segment_level < 0.5 ? 1.0 : widths[int(u_segment_level) - 1];
    float next = u_segment_level >= u_segment_last ? here : widths[int(u_segment_level)];
    return mix(here, next, m);
}

// For the vertex at curve parameter t drawn at level `level`: the parameters of the next
// level's rows below and above it, its share of the way between them, and whether it leaves
// there (the root and the tip never do; neither do rows the next level keeps)
bool segment_leaves(float t, float level, out float t_lo, out float t_hi, out float share) {
    float s = u_subdivisions;
    float row = floor(t * s + 0.5);
    float step = exp2(level + 1.0);
    float lo = row - mod(row, step);
    float hi = min(lo + step, s);
    t_lo = lo / s;
    t_hi = hi / s;
    share = hi > lo ? (row - lo) / (hi - lo) : 0.0;
    return row != lo && row != s;
}
