/* Command-line options shared by jade's commands, table-driven so every
 * command gets the same parsing, help text and errors. */
#ifndef JD_OPTIONS_H
#define JD_OPTIONS_H

#include "renderer.h"
#include "mesh_load.h"

typedef struct jd_options {
    const char *mesh;         /* NULL: the default asset */
    const char *out;
    const char *sheet;
    const char *material;
    const char *mode_list;    /* bench: "all" or one mode */
    const char *profile;      /* device profile to emulate, or NULL */
    const char *platform;     /* headless, x11, drm */
    const char *screenshot;   /* view: PNG written after the last frame */
    const char *pfm;          /* reference: linear image */
    const char *mask_out;     /* reference: object mask */
    const char *sheet_ref;    /* render --sheet: a reference picture shown first */
    const char *mask_in;      /* metric: the object's pixels */
    const char *positional[2]; /* metric: the two pictures */
    int num_positional;
    int samples, threads, seed, quiet;
    float ref_error, window_mm;
    int pixel_samples;
    int bounces;            /* jade reference: inter-reflection rounds */
    int volume;             /* jade reference: the diffusion equation in the body */
    int single_scatter;     /* jade reference: single scattering traced per pixel */
    float volume_mm;
    const char *drm_device, *connector, *display_mode;
    int rotation;
    int kms;           /* kiosk: jd_kms_api (platform.h) */
    int atomic;        /* kiosk --atomic: kms atomic */
    int gpu_enlarge;   /* kiosk: no display-engine scaling of the tier's picture */
    int wait_display;
    int width, height;
    int frames;
    int budget_mb;
    int json;
    float log_every;     /* kiosk, bench: seconds between health lines, 0 = none */
    int cycle_materials; /* bench */
    int compile_only;    /* info --compile */
    int list_materials;  /* info --materials */
    int list_boards;     /* info --boards */
    int unroll_loops;    /* info --compile --unroll-loops N */
    const char *device;  /* bench --device: a board of the frame-cost model */
    float light_speed;   /* kiosk: degrees per second */
    float light_step;    /* render, reference: degrees the light turns from one frame to the next */
    const char *config;  /* kiosk: the configuration file */
    float idle_s;        /* kiosk: seconds without input before the camera returns */
    int fullscreen;      /* set by the kiosk: a window platform fills the screen */
    jd_load_desc load;
    jd_renderer_desc rdesc;
    jd_scene scene;
    int has_sigma_s, has_sigma_a, has_eta, has_budget, has_material;
    int medium_said; /* the file's medium has been said (once a run) */
    int colour_said; /* the material from the model's colours has been said */
} jd_options;

enum { JD_OPT_RENDER = 1, JD_OPT_BENCH = 2, JD_OPT_INFO = 4, JD_OPT_VIEW = 8, JD_OPT_KIOSK = 16, JD_OPT_REFERENCE = 32, JD_OPT_METRIC = 64,
       JD_OPT_CONVERT = 128 };

void jd_options_defaults(jd_options *o);
/* Frame `frame`'s light azimuth with --light-step: in double, rounded once,
 * so that it is the picture of a run given that azimuth, bit for bit. */
float jd_options_light_at(float azimuth, float step, long frame);
/* Parses argv[first..argc); prints a one-line error and returns 0 on bad input.
 * Returns -1 after printing help. */
int jd_options_parse(jd_options *o, int command, const char *cmdname, int argc, char **argv, int first);
void jd_options_help(int command, const char *cmdname, const char *summary);
/* Applies --material and explicit coefficients to the scene. */
int jd_options_finish(jd_options *o, const char *cmdname);
/* Options from a file of "key = value" lines (keys are the options without
 * "--"; flags take yes/no, true/false, on/off or 1/0; '#' starts a comment),
 * checked exactly as on the command line; errors name the file and line.
 * String values live in `store` (cap bytes), which must outlive `o`.
 * Returns 1, or 0 after printing one line. */
int jd_options_parse_file(jd_options *o, int command, const char *cmdname, const char *path, char *store, size_t cap);
/* What the loaded file says of its material: its medium (glTF's
 * translucency extensions), then its extras.jade_material, which wins;
 * the command line's --material, --sigma-s/-a, --eta and --mm-per-unit win
 * over both. Says once on stderr what it took and what jade cannot show;
 * an unknown jade_material is said and ignored. */
void jd_options_file_material(jd_options *o, const jd_load_stats *st, const char *path, const char *cmdname);
/* Parse, help and finish in one: returns -1 to go on, else the exit code. */
int jd_options_command(jd_options *o, int command, const char *cmdname, const char *summary, int argc,
                       char **argv);

#endif
