/* The exact albedo of a half-space over the dipole's Rd_total, tabulated
 * (core/albedo_table.c, made by tools/make_albedo_table.sh): read through
 * jd_albedo_ratio in material.h. */
#ifndef JD_ALBEDO_TABLE_H
#define JD_ALBEDO_TABLE_H

#ifdef __cplusplus
extern "C" {
#endif

enum { JD_ALBEDO_ETAS = 41, JD_ALBEDO_XS = 65 };
extern const float jd_albedo_ratio_table[JD_ALBEDO_ETAS][JD_ALBEDO_XS];

#ifdef __cplusplus
}
#endif

#endif
