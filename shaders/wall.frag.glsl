// The side walls: the wall colour, diffuse light with an ambient part (walls are vertical, so
// "relative to level ground" would leave them black).
uniform vec3 wall_colour, light;
flat in vec3 normal;
out vec4 colour;

void main()
{
    colour = vec4(wall_colour * (0.55 + 0.45 * max(dot(normal, light), 0.0)), 1.0);
}
