/* The GLSL sources of shaders/NAME[.STAGE].glsl, embedded at build time (shaders/embed_shaders.cmake),
 * without their #version line, which render_link_program states. */
#ifndef INDENTMAP_RENDER_SHADERS_H
#define INDENTMAP_RENDER_SHADERS_H

extern const char im_shader_patch_colour[]; /* shared by the fragment shaders that colour patches */
extern const char im_shader_fullscreen_vert[];
extern const char im_shader_contact_frag[];
extern const char im_shader_height_frag[];
extern const char im_shader_surface_vert[];
extern const char im_shader_surface_frag[];
extern const char im_shader_punch_vert[];
extern const char im_shader_punch_frag[];
extern const char im_shader_wall_vert[];
extern const char im_shader_wall_frag[];

#endif
