/* The scalar path of stereoblend.h in a translation unit of its own (built with
   -DSBL_NO_SIMD), so that test_simd can run both paths in one binary. */
#define STEREOBLEND_STATIC
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"

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
