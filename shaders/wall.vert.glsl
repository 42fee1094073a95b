// The surface's side walls, from its edge down to a flat base, so that it reads as a solid block:
// one quad (six vertices) per mesh cell along the four edges, counter-clockwise from the corner
// (0, 0) seen from above. Corners as in surface.vert.glsl.
uniform sampler2D corners;     // (cells.x + 1) x (cells.y + 1), R32F, heights / delta
uniform ivec2 cells;
uniform ivec2 grid;
uniform int stride;
uniform float exaggeration;
uniform float base;            // world height of the block's bottom
uniform mat4 view_projection;
flat out vec3 normal;

// (along the edge, 0 bottom / 1 top) for the six vertices of a quad.
const ivec2 CORNER[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));

void main()
{
    int segment = gl_VertexID / 6;
    ivec2 k = CORNER[gl_VertexID % 6];
    ivec2 corner;
    if (segment < cells.x) {
        corner = ivec2(segment + k.x, 0);
        normal = vec3(0.0, -1.0, 0.0);
    } else if (segment < cells.x + cells.y) {
        corner = ivec2(cells.x, segment - cells.x + k.x);
        normal = vec3(1.0, 0.0, 0.0);
    } else if (segment < 2 * cells.x + cells.y) {
        corner = ivec2(cells.x - (segment - cells.x - cells.y) - k.x, cells.y);
        normal = vec3(0.0, 1.0, 0.0);
    } else {
        corner = ivec2(0, cells.y - (segment - 2 * cells.x - cells.y) - k.x);
        normal = vec3(-1.0, 0.0, 0.0);
    }
    float top = exaggeration * texelFetch(corners, corner, 0).r;
    gl_Position = view_projection * vec4(vec2(min(corner * stride, grid)), k.y == 1 ? top : base, 1.0);
}
