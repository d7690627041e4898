/* One build of stereoblend.h with SBL_SHORTCUTS = SC_MASK behind two entry points, for
   bench/shortcuts.c (compiled once per mask; every library function is static here, so
   the builds link side by side in one program). */
#define STEREOBLEND_STATIC
#define STEREOBLEND_IMPLEMENTATION
#define SBL_SHORTCUTS SC_MASK
#include "../stereoblend.h"

#define SC_CAT2(a, b) a##b
#define SC_CAT(a, b) SC_CAT2(a, b)

sbl_result SC_CAT(sc_temporal_, SC_MASK)(const sbl_temporal_desc *desc, const sbl_frame *frame,
                                         const sbl_history *history, sbl_temporal_output *out,
                                         void *scratch, size_t bytes);
sbl_result SC_CAT(sc_stereo_, SC_MASK)(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                       const sbl_eye *target, const sbl_eye *source,
                                       sbl_image out_color, sbl_image out_length,
                                       void *scratch, size_t bytes);

sbl_result SC_CAT(sc_temporal_, SC_MASK)(const sbl_temporal_desc *desc, const sbl_frame *frame,
                                         const sbl_history *history, sbl_temporal_output *out,
                                         void *scratch, size_t bytes)
{
    return sbl_temporal_filter(desc, frame, history, out, 0, frame->color.height, scratch, bytes);
}

sbl_result SC_CAT(sc_stereo_, SC_MASK)(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                       const sbl_eye *target, const sbl_eye *source,
                                       sbl_image out_color, sbl_image out_length,
                                       void *scratch, size_t bytes)
{
    return sbl_stereo_blend(desc, target_eye, target, source, out_color, out_length, 0,
                            out_color.height, scratch, bytes);
}
