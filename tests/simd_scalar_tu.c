/* The scalar path of stereoblend.h for test_simd, beside the path under test in one
   binary. `make check` takes it from the scalar configuration's object with its global
   symbols renamed scalar_<name> (objcopy; then this file is built with
   SIMD_SCALAR_RENAMED and holds the wrappers only), or, where objcopy is missing, from
   a static copy of the implementation built here with -DSBL_NO_SIMD. */
#ifdef SIMD_SCALAR_RENAMED
#define sbl_temporal_filter_frame scalar_sbl_temporal_filter_frame
#define sbl_stereo_blend_frame scalar_sbl_stereo_blend_frame
#include "../stereoblend.h"
const char *scalar_tst_simd_name(void); /* tests/sbl_impl.c's tst_simd_name, renamed */
#define SBL_SIMD_NAME scalar_tst_simd_name()
#else
#define STEREOBLEND_STATIC
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#endif

const char *scalar_simd_name(void);
sbl_result scalar_temporal_filter(const sbl_temporal_desc *d, const sbl_frame *f,
                                  const sbl_history *h, const sbl_temporal_output *o);
sbl_result scalar_stereo_blend(const sbl_stereo_desc *d, const sbl_eye *l, const sbl_eye *r,
                               sbl_image ol, sbl_image orr);

const char *scalar_simd_name(void) { return SBL_SIMD_NAME; }

sbl_result scalar_temporal_filter(const sbl_temporal_desc *d, const sbl_frame *f,
                                  const sbl_history *h, const sbl_temporal_output *o)
{
    return sbl_temporal_filter_frame(d, f, h, o);
}

sbl_result scalar_stereo_blend(const sbl_stereo_desc *d, const sbl_eye *l, const sbl_eye *r,
                               sbl_image ol, sbl_image orr)
{
    return sbl_stereo_blend_frame(d, l, r, ol, orr);
}
