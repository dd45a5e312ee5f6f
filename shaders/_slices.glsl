// Texels of the slices' data textures (render/slices.py): the normal, turned up, with the length
// the mip averaging gave it (shorter where blades disagree), and the density threshold. It is
// not normalised here: the lambert term of the average normal is the average lambert term.
vec3 slice_normal(vec4 data) { return data.rgb * 2.0 - 1.0; }
