#version 450
/* bb_occlude.frag: nothing to write; the occlusion query counts the box's
 * fragments that pass the depth test (colour and depth writes off). */
void main()
{
}
