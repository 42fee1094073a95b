// Contact map: one texel per patch, integer upscaling, boundary frame, anti-aliased (or aliased) circle.
// After shaders/patch_colour.glsl; code 259: not in contact, the background.
uniform usampler2D codes;      // nx x ny, R16UI
uniform vec3 background, line_colour;
uniform ivec2 grid;            // nx, ny
uniform int scale;             // pixels per patch
uniform int border;            // width of the boundary frame in pixels
uniform vec3 circle;           // centre (pixels from the data's lower-left corner) and radius; r <= 0: none
uniform float circle_width;    // pixels
uniform int circle_aliased;    // 1: a pixel at least half covered by the line takes its colour, others none
out vec4 colour;

// Fraction of a pixel (box filter across the line) covered by the circle's line: the overlap of
// [d - 1/2, d + 1/2] with [-w/2, w/2], d the distance from the pixel centre to the circle.
float circle_coverage(vec2 position)
{
    if (circle.z <= 0.0)
        return 0.0;
    float d = length(position - circle.xy) - circle.z;
    float half_width = 0.5 * circle_width;
    return clamp(min(d + 0.5, half_width) - max(d - 0.5, -half_width), 0.0, 1.0);
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(border);
    vec3 c;
    if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, grid * scale)))
        c = line_colour;
    else
        c = patch_colour(texelFetch(codes, pixel / scale, 0).r, background);
    float coverage = circle_coverage(gl_FragCoord.xy - vec2(border));
    if (circle_aliased != 0)
        coverage = step(0.5, coverage);
    c = mix(c, line_colour, coverage);
    colour = vec4(c, 1.0);
}
