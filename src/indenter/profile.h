/* Internal: the profile kinds' geometry and smooth-contact forms (indenter.h, "User-given profiles"),
 * for indenter.c. Lengths in the units of delta; loads for the modulus e_star. */
#ifndef INDENTMAP_INDENTER_PROFILE_H
#define INDENTMAP_INDENTER_PROFILE_H

#include "indentmap/indenter.h"

/* z(r) of an axisymmetric profile, +INFINITY beyond its last sample. */
double profile_axisymmetric_height(const im_profile *profile, double r);
/* z at offset (dx, dy) from the axis of a 2-D profile, +INFINITY outside its samples. */
double profile_field_height(const im_profile *profile, double dx, double dy);

/* Axisymmetric profiles only: Sneddon's smooth contact (the flat punch's beyond full contact). */
double profile_contact_radius(const im_profile *profile, double w);
double profile_load(const im_profile *profile, double e_star, double w);
double profile_approach_for_load(const im_profile *profile, double e_star, double n);
double profile_radius_for_load(const im_profile *profile, double e_star, double n);

#endif
