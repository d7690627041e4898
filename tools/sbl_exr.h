/* sbl_exr.h - minimal OpenEXR float I/O for the stereoblend tools and bench.
 *
 * OpenEXR is an optional dependency of the tools only (stereoblend.h never
 * needs it). Build sbl_exr.c with OpenEXR's C library (OpenEXRCore, 3.1+):
 *     cc ... tools/sbl_exr.c $(pkg-config --cflags --libs OpenEXR)
 * or, without it, with -DSBL_NO_EXR: every call then fails with
 * "built without OpenEXR" so the tools still link.
 *
 * All images are interleaved float, row 0 = top (EXR increasing y),
 * width/height = the data window of the file.
 */
#ifndef SBL_EXR_H
#define SBL_EXR_H

#ifdef __cplusplus
extern "C" {
#endif

/* Read the named channels (e.g. "ViewLayer.Combined.R") of a scanline or
 * tiled, single- or multi-part EXR into a freshly malloc'ed interleaved
 * float array of width*height*channel_count values (free() it). Half and
 * uint channels are converted to float. The first part holding all the
 * names is used. Returns 0 on success, else nonzero with a message in err
 * (err may be NULL). */
int sbl_exr_read(const char *path, const char *const *channel_names,
                 int channel_count, float **out, int *width, int *height,
                 char *err, int err_size);

/* Write an interleaved float image with `channels` channels as a float32,
 * ZIP compressed scanline EXR. channel_names NULL (only for 1..4 channels)
 * -> "Y" / "R","G" / "R","G","B" / "R","G","B","A". Returns 0 on success. */
int sbl_exr_write(const char *path, const float *data, int width, int height,
                  int channels, const char *const *channel_names,
                  char *err, int err_size);

/* Nonzero if built with OpenEXR (i.e. not with -DSBL_NO_EXR). */
int sbl_exr_available(void);

#ifdef __cplusplus
}
#endif

#endif /* SBL_EXR_H */
