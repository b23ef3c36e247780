# Sourced by the GUI tests of Ellipse Splatting (tests/render/meshlab_gui_splatting.sh for
# MeshLab 2020.09, scripts/hosts/render_e2e.sh for 2022.02 and 2025.07):
#   splat_sphere_ply FILE [bare]      1500 points on a unit sphere with outward normals (ASCII
#                                     PLY): sparse enough for gaps between MeshLab's points;
#                                     with "bare" the same points without normals
#   splat_pixel_classes IMAGE CROP    "olive grey": pixel counts in the CROP (ImageMagick
#                                     geometry WxH+X+Y, the 3D view) by colour class: MeshLab's
#                                     points are olive (2020.09) or yellow (2022.02, 2025.07):
#                                     red and green well above blue; the splats' default is grey;
#                                     neither are the background gradient (blue) and the
#                                     trackball's red axis line (red above green and blue)
#   splat_pixel_change BEFORE AFTER CROP
#                                     "filled emptied": pixels of the CROP drawn (olive or grey)
#                                     in AFTER but not in BEFORE, and the other way round: the
#                                     gaps between points that splats close, what they uncover

splat_sphere_ply() {
  awk -v bare="${2:-}" 'BEGIN {
    n = 1500; golden = 3.14159265 * (3 - sqrt(5));
    print "ply\nformat ascii 1.0\nelement vertex " n;
    print "property float x\nproperty float y\nproperty float z";
    if (bare != "bare") print "property float nx\nproperty float ny\nproperty float nz";
    print "end_header";
    for (i = 0; i < n; i++) {
      y = 1 - 2 * (i + 0.5) / n; r = sqrt(1 - y * y);
      x = r * cos(golden * i); z = r * sin(golden * i);
      if (bare == "bare") printf "%f %f %f\n", x, y, z;
      else printf "%f %f %f %f %f %f\n", x, y, z, x, y, z;
    }
  }' > "$1"
}

# awk: the class of the pixel with channels r, g, b: 1 olive, 2 grey, 0 neither.
splat_pixel_class_awk='function pixel_class(r, g, b) {
  if (r - b > 25) return g - b > 25 ? 1 : 0;
  return b - r <= 25 && r > 30 ? 2 : 0 }'

splat_pixel_classes() {
  splat_pixel_rgb "$1" "$2" | awk "$splat_pixel_class_awk"'
    { c = pixel_class($1, $2, $3); if (c == 1) olive++; else if (c == 2) grey++ }
    END { printf "%d %d\n", olive, grey }'
}

splat_pixel_rgb() { # IMAGE CROP: "r g b", a line per pixel
  convert "$1" -crop "$2" -depth 8 txt:- | awk -F'[(),]' 'NR > 1 { print $3, $4, $5 }'
}

splat_pixel_change() {
  paste -d' ' <(splat_pixel_rgb "$1" "$3") <(splat_pixel_rgb "$2" "$3") | awk "$splat_pixel_class_awk"'
    { before = pixel_class($1, $2, $3) != 0; after = pixel_class($4, $5, $6) != 0;
      if (after && !before) filled++; else if (before && !after) emptied++ }
    END { printf "%d %d\n", filled, emptied }'
}
