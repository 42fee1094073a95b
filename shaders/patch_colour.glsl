// Shared by the fragment shaders that colour patches (render_link_program puts it after the #version
// line and before the shader's own source). Patch codes, computed on the CPU by render_patch_code
// (render/context.h): 0..255 an entry of the colour map's table, 256 under the norm, 257 over it,
// 258 bad (NaN), 259 none of these (the shader's own colour: background, surface), 260 under tension
// (a negative force: adhesion).
uniform sampler2D table;       // 256 x 1, RGBA8: the colour map's exact table
uniform vec3 under_colour, over_colour, bad_colour, tensile_colour;

vec3 patch_colour(uint code, vec3 otherwise)
{
    if (code < 256u)
        return texelFetch(table, ivec2(int(code), 0), 0).rgb;
    if (code == 256u)
        return under_colour;
    if (code == 257u)
        return over_colour;
    if (code == 258u)
        return bad_colour;
    if (code == 260u)
        return tensile_colour;
    return otherwise;
}
