/* A file a model names (a glTF buffer or image, an OBJ's material library or
 * texture), read from beside the model inside the loader's child process.
 * Internal: not installed. */
#ifndef JD_FILE_BESIDE_H
#define JD_FILE_BESIDE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* `name` in model_path's folder, whole (NUL-terminated past *len; malloc'd),
 * or NULL with a reason in why: a name that is not plain and relative (no
 * "..", no absolute path, no '\\', ':' or '%'), a file that is not regular
 * (a FIFO is opened without blocking and refused), empty or over max_bytes. */
uint8_t *jd_file_beside(const char *model_path, const char *name, size_t max_bytes, size_t *len, char *why,
                        size_t cap);

#ifdef __cplusplus
}
#endif
#endif
