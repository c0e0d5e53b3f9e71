#ifndef JD_COMMANDS_H
#define JD_COMMANDS_H
#include <stdint.h>
#include "session.h"
int jd_cmd_render(int argc, char **argv);
int jd_cmd_info(int argc, char **argv);
int jd_cmd_bench(int argc, char **argv);
int jd_cmd_view(int argc, char **argv);
int jd_cmd_kiosk(int argc, char **argv);
int jd_cmd_metric(int argc, char **argv);
int jd_cmd_reference(int argc, char **argv);
int jd_cmd_convert(int argc, char **argv);
int jd_render_sheet(jd_session *s, jd_options *o, uint8_t *px);
#endif
