# A .surfel layer saved as PLY with normals and radii (`-m vn vr`) loads again; that layer
# has no ellipse attributes, so saving it as .surfel writes zero axes.
source "$E2E_COMMON"
"$SURFEL_FIXTURE" in.surfel 300
"$RUN_MESHLABSERVER" -i in.surfel -o out.ply -m vn vr
"$RUN_MESHLABSERVER" -i out.ply -o back.surfel
"$SURFEL_CHECK" back.surfel --count 300 --require-no-ellipses
