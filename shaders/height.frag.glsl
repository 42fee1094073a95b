// Height field: colour map + Lambert hill-shading from per-patch normals, optional contact outline.
// After shaders/patch_colour.glsl (code 259 is not used here).
uniform usampler2D codes;      // nx x ny, R16UI
uniform sampler2D heights;     // nx x ny, R32F, heights in units of the patch side
uniform usampler2D contact;    // nx x ny, R8UI, 1 in contact (all 0 without a contact field)
uniform vec3 line_colour, outline_colour;
uniform ivec2 grid;
uniform int scale, border, outline_width;
uniform vec3 light;            // unit vector towards the light
uniform float shading, exaggeration;
out vec4 colour;

// Height of a neighbour, or the patch's own height outside the grid or where it is NaN.
float height_at(ivec2 cell, float own)
{
    if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, grid)))
        return own;
    float h = texelFetch(heights, cell, 0).r;
    return isnan(h) ? own : h;
}

// Lambert's law relative to a flat patch: 1 on flat ground, brighter facing the light.
float hill_shade(ivec2 cell)
{
    float own = texelFetch(heights, cell, 0).r;
    float left = height_at(cell - ivec2(1, 0), own), right = height_at(cell + ivec2(1, 0), own);
    float down = height_at(cell - ivec2(0, 1), own), up = height_at(cell + ivec2(0, 1), own);
    float span_x = (cell.x > 0 && cell.x < grid.x - 1) ? 2.0 : 1.0;
    float span_y = (cell.y > 0 && cell.y < grid.y - 1) ? 2.0 : 1.0;
    vec2 slope = exaggeration * vec2((right - left) / span_x, (up - down) / span_y);
    vec3 normal = normalize(vec3(-slope, 1.0));
    return max(dot(normal, light), 0.0) / light.z;
}

bool in_contact(ivec2 cell)
{
    if (any(lessThan(cell, ivec2(0))) || any(greaterThanEqual(cell, grid)))
        return false;
    return texelFetch(contact, cell, 0).r != 0u;
}

// Inside a contact patch, within outline_width pixels of an edge shared with a non-contact patch.
bool on_outline(ivec2 cell, ivec2 inside)
{
    if (!in_contact(cell))
        return false;
    int far = scale - 1 - outline_width;
    return (inside.x < outline_width && !in_contact(cell - ivec2(1, 0))) ||
           (inside.x > far && !in_contact(cell + ivec2(1, 0))) ||
           (inside.y < outline_width && !in_contact(cell - ivec2(0, 1))) ||
           (inside.y > far && !in_contact(cell + ivec2(0, 1)));
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(border);
    if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, grid * scale))) {
        colour = vec4(line_colour, 1.0);
        return;
    }
    ivec2 cell = pixel / scale;
    uint code = texelFetch(codes, cell, 0).r;
    vec3 c = patch_colour(code, bad_colour);
    if (code != 258u)
        c = clamp(c * mix(1.0, hill_shade(cell), shading), 0.0, 1.0);
    if (on_outline(cell, pixel - cell * scale))
        c = outline_colour;
    colour = vec4(c, 1.0);
}
