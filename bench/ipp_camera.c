/* Instructions per pixel of the camera plans (valgrind callgrind, as bench/ipp.sh
   counts): the temporal filter with the camera source (a moving camera, ~(0.37, -0.21)
   px at the depth of the easy case) and the stereo blend of a pinhole rig, 640x360 RGB,
   with normals and ids in every G-buffer ("nid") or without ("plain"). The lane plans of
   both took normals / ids in session 11 (before: one pixel at a time).
     cc -std=c99 -O2 [-mavx2 -mfma] bench/ipp_camera.c -o ipp_camera -lm
     valgrind --tool=callgrind --toggle-collect=sbl_temporal_filter ./ipp_camera nid
   (divide Ir by 640 * 360; each call runs once; prints a hash of both outputs) */
#define STEREOBLEND_IMPLEMENTATION
#ifndef HDR
#define HDR "../stereoblend.h"
#endif
#include HDR
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#define W 640
#define H 360
static float *fa(size_t n) { float *p = calloc(n, sizeof(float)); if (!p) exit(2); return p; }
int main(int argc, char **argv)
{
    size_t n = (size_t)W * H, i;
    unsigned s = 999u;
    float *col = fa(n * 3), *hist = fa(n * 3), *hl = fa(n), *dep = fa(n), *pdep = fa(n), *nr = fa(n * 3),
          *pnr = fa(n * 3), *id = fa(n), *pid = fa(n), *out = fa(n * 3), *on = fa(n), *sout = fa(n * 3);
    sbl_camera cam[2];
    sbl_intrinsics k;
    float pose[2][16];
    int e, q, nid = argc > 1 && strcmp(argv[1], "plain") != 0;
    size_t bytes = sbl_temporal_scratch_size(W, 3);
    void *scratch = malloc(bytes);
    for (i = 0; i < n; ++i) {
        int x = (int)(i % W), y = (int)(i / W), c;
        for (c = 0; c < 3; ++c) {
            s = s * 1664525u + 1013904223u;
            col[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c) + (float)(s >> 8) * (1.0f / 16777216.0f) * 0.2f;
            hist[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c);
            nr[i * 3 + c] = pnr[i * 3 + c] = c == 2 ? 1.0f : 0.01f * (float)c;
        }
        hl[i] = 8.0f;
        dep[i] = pdep[i] = 2.0f + 0.001f * (float)y;
        id[i] = pid[i] = 1.0f;
    }
    k.fx = k.fy = 800.0f; k.cx = 320.0f; k.cy = 180.0f;
    for (e = 0; e < 2; ++e) {
        for (q = 0; q < 16; ++q) pose[e][q] = q % 5 == 0 ? 1.0f : 0.0f;
        if (e) { pose[e][3] = -0.00093f; pose[e][7] = 0.00052f; } /* ~0.37, -0.21 px at z 2 */
        sbl_camera_from_pinhole(&cam[e], &k, pose[e], SBL_AXES_OPENCV, 0, W, H);
    }
    {
        sbl_temporal_desc td; sbl_frame f; sbl_history hi; sbl_temporal_output o;
        memset(&td, 0, sizeof td); memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi); memset(&o, 0, sizeof o);
        td.source = SBL_TEMPORAL_CAMERA;
        f.color = sbl_image_make(col, W, H, 3); f.gbuffer.depth = sbl_image_make(dep, W, H, 1); f.camera = &cam[1];
        hi.color = sbl_image_make(hist, W, H, 3); hi.length = sbl_image_make(hl, W, H, 1);
        hi.gbuffer.depth = sbl_image_make(pdep, W, H, 1); hi.camera = &cam[0];
        if (nid) {
            f.gbuffer.normals = sbl_image_make(nr, W, H, 3); f.gbuffer.ids = sbl_image_make(id, W, H, 1);
            hi.gbuffer.normals = sbl_image_make(pnr, W, H, 3); hi.gbuffer.ids = sbl_image_make(pid, W, H, 1);
        }
        o.color = sbl_image_make(out, W, H, 3); o.length = sbl_image_make(on, W, H, 1);
        if (sbl_temporal_filter(&td, &f, &hi, &o, 0, H, scratch, bytes) != SBL_OK) return 1;
    }
    {
        sbl_stereo_desc sd; sbl_eye te, se;
        memset(&sd, 0, sizeof sd); memset(&te, 0, sizeof te); memset(&se, 0, sizeof se);
        sd.rig = SBL_RIG_PINHOLE;
        sd.pinhole.eye[0] = sd.pinhole.eye[1] = k;
        for (q = 0; q < 16; ++q) sd.pinhole.right_from_left[q] = q % 5 == 0 ? 1.0f : 0.0f;
        sd.pinhole.right_from_left[3] = -0.065f;
        sd.pinhole.axes = SBL_AXES_OPENCV;
        te.color = sbl_image_make(out, W, H, 3); te.length = sbl_image_make(on, W, H, 1);
        te.gbuffer.depth = sbl_image_make(dep, W, H, 1);
        se.color = sbl_image_make(col, W, H, 3); se.length = sbl_image_make(hl, W, H, 1);
        se.gbuffer.depth = sbl_image_make(pdep, W, H, 1);
        if (nid) {
            te.gbuffer.normals = sbl_image_make(nr, W, H, 3); te.gbuffer.ids = sbl_image_make(id, W, H, 1);
            se.gbuffer.normals = sbl_image_make(pnr, W, H, 3); se.gbuffer.ids = sbl_image_make(pid, W, H, 1);
        }
        if (sbl_stereo_blend(&sd, SBL_EYE_LEFT, &te, &se, sbl_image_make(sout, W, H, 3), sbl_image_make(NULL, 0, 0, 1),
                             0, H, scratch, bytes) != SBL_OK) return 1;
    }
    {
        unsigned long long h = 14695981039346656037ull;
        const unsigned char *c;
        for (c = (const unsigned char *)out; c < (const unsigned char *)(out + n * 3); ++c) h = (h ^ *c) * 1099511628211ull;
        for (c = (const unsigned char *)sout; c < (const unsigned char *)(sout + n * 3); ++c) h = (h ^ *c) * 1099511628211ull;
        printf("hash %016llx\n", h);
    }
    return 0;
}
