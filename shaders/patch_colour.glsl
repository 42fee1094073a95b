// Shared by the fragment shaders that colour patches (render_link_program puts it after the #version
// line and before the shader's own source). Patch codes, computed on the CPU by render_force_code
// (render/context.h): 0..255 an entry of the colour map's table, 256 under the norm, 257 over it,
// 258 bad (NaN), 259 none of these (the shader's own colour: background, surface); 512 plus such a
// code (0..257) for a patch under tension (a negative force: adhesion), through the tension norm.
uniform sampler2D table;           // 256 x 1, RGBA8: the colour map's exact table
uniform sampler2D tension_table;   // 256 x 1, RGBA8: the tension ramp's
uniform vec3 under_colour, over_colour, bad_colour, tension_under, tension_over;

vec3 norm_colour(uint code, sampler2D entries, vec3 under, vec3 over, vec3 otherwise)
{
    if (code < 256u)
        return texelFetch(entries, ivec2(int(code), 0), 0).rgb;
    if (code == 256u)
        return under;
    if (code == 257u)
        return over;
    if (code == 258u)
        return bad_colour;
    return otherwise;
}

vec3 patch_colour(uint code, vec3 otherwise)
{
    if (code >= 512u)
        return norm_colour(code - 512u, tension_table, tension_under, tension_over, otherwise);
    return norm_colour(code, table, under_colour, over_colour, otherwise);
}
