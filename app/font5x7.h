#ifndef JD_FONT5X7_H
#define JD_FONT5X7_H
#include <stdint.h>
/* Draws upper-case text, digits and ()-.:/, at (x, y) top-left, `scale` pixels per dot. */
void jd_font_draw(uint8_t *rgba, int w, int h, int x, int y, int scale, const char *text, const uint8_t color[3]);
#endif
