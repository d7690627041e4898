/* sbl_dataset.h - loader for rendered stereo sequences in the layout of
 * shared/data/atrium (see its README.md):
 *
 *   DIR/meta.json      frames, resolution [w,h], ref_spp, ladder_frames, ladder_spp
 *   DIR/cameras.json   world_to_cam, cam_to_world, proj: [frame][eye] 4x4 row-major
 *                      (nested rows or flat 16), focal_px (scalar, [frame] or
 *                      [frame][eye]), baseline, optional resolution, clip [near,far]
 *   DIR/exr/noisy/L_0000.exr   ViewLayer.Combined.{R,G,B}   (eye L = 0, R = 1)
 *   DIR/exr/ref/L_0000.exr     same channels (optional)
 *   DIR/exr/gbuf/L_0000.exr    ViewLayer.Depth.Z, Normal.{X,Y,Z}, IndexOB.X, Vector.{X,Y}
 *   DIR/exr/ladder/L_f0008_s016.exr  ViewLayer.Combined.{R,G,B}
 *
 * Images are W*H (row 0 = top), interleaved float. Needs sbl_exr.c.
 * Loads are independent of each other and may run in parallel.
 */
#ifndef SBL_DATASET_H
#define SBL_DATASET_H

#ifdef __cplusplus
extern "C" {
#endif

#define SBL_DATASET_MAX_LADDER 16

typedef struct sbl_dataset {
    char dir[1024];
    int frames, width, height;
    int ref_spp;                         /* 0 if meta.json has none */
    int ladder_frames[SBL_DATASET_MAX_LADDER], ladder_frame_count;
    int ladder_spp[SBL_DATASET_MAX_LADDER], ladder_spp_count;
    /* Per frame and eye (0 = L, 1 = R), row-major: m[4*row + col].
     * cam_to_world is Blender's camera matrix (camera looks down -z, +y up);
     * proj is OpenGL-style: u = (ndc_x + 1)/2 W, v = (1 - ndc_y)/2 H. */
    float (*world_to_cam)[2][16];
    float (*cam_to_world)[2][16];
    float (*proj)[2][16];
    float (*focal_px)[2];                /* fx = fy, pixels */
    float baseline;                      /* metres; R = L moved along camera +x */
    float clip_near, clip_far;           /* 0 if cameras.json has no clip */
} sbl_dataset;

/* All arrays W*H*channels floats, malloc'ed (free with sbl_dataset_frame_free). */
typedef struct sbl_dataset_frame {
    float *noisy;   /* 3: RGB, 1 spp */
    float *ref;     /* 3: RGB reference, NULL if the file does not exist */
    float *depth;   /* 1: planar depth along the view axis (m); background 1e10 */
    float *normal;  /* 3: world-space unit normal; 0 on background */
    float *id;      /* 1: object index (IndexOB), 0 = background */
    float *motion;  /* 2: (mx, my): the point seen at pixel centre (u, v) was at
                       (u + mx, v + my) in the previous frame, pixels, y DOWN */
} sbl_dataset_frame;

/* Parse DIR/meta.json and DIR/cameras.json. Returns 0 on success, else
 * nonzero with a message in err (may be NULL); ds is then zeroed. */
int sbl_dataset_open(sbl_dataset *ds, const char *dir, char *err, int err_size);
void sbl_dataset_close(sbl_dataset *ds);

/* Load noisy, ref (if present), gbuf of (frame, eye). Returns 0 on success;
 * on failure nothing is left allocated in out. */
int sbl_dataset_load(const sbl_dataset *ds, int frame, int eye, sbl_dataset_frame *out,
                     char *err, int err_size);
void sbl_dataset_frame_free(sbl_dataset_frame *f);

/* Load the ladder RGB render of (frame, eye) at spp samples into *rgb
 * (malloc'ed, W*H*3). Nonzero if missing or unreadable. */
int sbl_dataset_load_ladder(const sbl_dataset *ds, int frame, int eye, int spp, float **rgb,
                            char *err, int err_size);

/* Path of one of the sequence's files ("noisy", "ref", "gbuf"); 0 on success. */
int sbl_dataset_path(const sbl_dataset *ds, const char *kind, int frame, int eye,
                     char *path, int path_size);

#ifdef __cplusplus
}
#endif

#endif /* SBL_DATASET_H */
