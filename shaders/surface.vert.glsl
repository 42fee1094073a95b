// The deformed surface as a mesh drawn with an index buffer, so that each corner is shaded once:
// gl_VertexID = b * (cells.x + 1) + a names corner (a, b), which lies at
// (min(a * stride, nx), min(b * stride, ny)) in patches, at the height (in patches) stored for it
// in `corners`.
uniform sampler2D corners;     // (cells.x + 1) x (cells.y + 1), R32F, heights / delta
uniform ivec2 cells;           // mesh cells along x and y
uniform ivec2 grid;            // patches nx, ny
uniform int stride;            // patches per mesh cell
uniform float exaggeration;
uniform mat4 view_projection;
out vec3 world;

void main()
{
    ivec2 corner = ivec2(gl_VertexID % (cells.x + 1), gl_VertexID / (cells.x + 1));
    vec2 xy = vec2(min(corner * stride, grid));
    world = vec3(xy, exaggeration * texelFetch(corners, corner, 0).r);
    gl_Position = view_projection * vec4(world, 1.0);
}
