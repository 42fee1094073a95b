// The deformed surface: each fragment takes the colour code and the normal of the patch it lies
// in. After shaders/patch_colour.glsl; code 259: not in contact, the surface colour.
uniform usampler2D codes;      // nx x ny, R16UI
uniform sampler2D heights;     // nx x ny, R32F, heights / delta
uniform vec3 surface_colour;
uniform ivec2 grid;
uniform float exaggeration, shading;
uniform vec3 light;            // unit vector towards the light
in vec3 world;
out vec4 colour;

float height_at(ivec2 cell)
{
    return texelFetch(heights, clamp(cell, ivec2(0), grid - 1), 0).r;
}

// Central differences of the patch heights (one-sided at the edges), exaggerated.
vec3 patch_normal(ivec2 cell)
{
    ivec2 left = max(cell - ivec2(1, 0), ivec2(0)), right = min(cell + ivec2(1, 0), grid - 1);
    ivec2 down = max(cell - ivec2(0, 1), ivec2(0)), up = min(cell + ivec2(0, 1), grid - 1);
    float span_x = float(max(right.x - left.x, 1)), span_y = float(max(up.y - down.y, 1));
    vec2 slope = exaggeration * vec2((height_at(right) - height_at(left)) / span_x,
                                     (height_at(up) - height_at(down)) / span_y);
    return normalize(vec3(-slope, 1.0));
}

void main()
{
    ivec2 cell = clamp(ivec2(floor(world.xy)), ivec2(0), grid - 1);
    vec3 c = patch_colour(texelFetch(codes, cell, 0).r, surface_colour);
    // Lambert's law relative to level ground: a level patch keeps its exact colour.
    float lambert = max(dot(patch_normal(cell), light), 0.0) / light.z;
    colour = vec4(clamp(c * (1.0 + shading * (lambert - 1.0)), 0.0, 1.0), 1.0);
}
