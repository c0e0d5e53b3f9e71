/* Touch screens and mice where there is no window system (the DRM kiosk):
 * a finger, or the mouse with its left button held, moving gives
 * JD_EVENT_DRAG in screen pixels. Through libinput on udev's seat0 where
 * jade was built with it; without it, no input (said by the description). */
#ifndef JD_INPUT_H
#define JD_INPUT_H

#include "platform.h"

typedef struct jd_input jd_input;

/* Never fails the display: NULL and a reason in why when there is no input
 * (no libinput, no permission, no seat). */
jd_input *jd_input_open(int screen_w, int screen_h, char *why, size_t cap);
/* How many touch or pointer devices it found. */
int jd_input_devices(const jd_input *in);
/* 1 and an event while there are some; never blocks. */
int jd_input_poll(jd_input *in, jd_event *ev);
void jd_input_close(jd_input *in);

#endif
