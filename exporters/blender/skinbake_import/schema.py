"""The image set's manifest.json, as the importer reads it: the format it accepts and the allowed
range of every key it checks (imageset.py reads and checks with these, and nothing else does).

    format            "skinbake-blender-image-set", format_version in FORMAT_VERSIONS
    ior, roughness    numbers in NUMBERS' ranges
    sss_radius_m, albedo_rgb            3 numbers in [0, TRIPLES[key]] (metres, albedo)
    files.ROLE        for each ROLE in FILES: path (a file name in the set), width and height in
                      FILE_PIXELS, channels (one of CHANNELS for .exr, PNG_TYPES for .png)
    brdf_lut          cos_nodes, phi_nodes >= 2 (files.brdf_lut is cos_nodes*phi_nodes x cos_nodes)
    exact             sun_direction (3 numbers, z > 0), optional sun_strength_w_m2 in SUN_STRENGTH_W_M2
    detail            flat (bool); when not flat tile_mm in TILE_MM, optional mean_normal_z in MEAN_NORMAL_Z
    general_fit       optional: cos_view_nodes (>= 2 ascending in [0, 1]), FIT_RGB (an RGB triple
                      >= 0 per node), FIT_NUMBERS in their ranges (FIT_OPTIONAL may be absent)
    family            optional: sub_counts (3 integers >= 1), slices (their product), files.ROLE for
                      ROLE in FAMILY_FILES (file, width, height; float EXR)
"""

VERSION = "1.1.0"               # the importer's version (bl_info and blender_manifest.toml say the same)
FORMAT = "skinbake-blender-image-set"
FORMAT_VERSIONS = (1,)          # manifest "format_version" values this importer understands
FILES = ("albedo", "brdf_lut", "roughness", "height", "normal")
NUMBERS = {"ior": (1.0, 3.0), "roughness": (0.0, 1.0)}
TRIPLES = {"sss_radius_m": 1.0, "albedo_rgb": 1.0}
FILE_PIXELS = (1, 65536)
SUN_STRENGTH_W_M2 = (0.0, 1e6)
TILE_MM = (0.5, 500.0)
MEAN_NORMAL_Z = (1e-3, 1.0)
FIT_RGB = ("subsurface_rgb", "glossy_rgb")
FIT_NUMBERS = {"subsurface_roughness": (0.0, 1.0), "glossy_roughness": (0.0, 1.0), "specular_alpha": (0.0, 1.0),
               "specular_ior": (1.0, 3.0)}
FIT_OPTIONAL = ("subsurface_roughness",)
FAMILY_FILES = ("family_lut", "family_coord", "albedo_map", "sss_radius_map")
# What files.ROLE.channels promises: EXR channel names (all float32, in the file's sorted order),
# PNG colour type (16 bits).
CHANNELS = {"R,G,B": ("B", "G", "R"), "R,G,B,A": ("A", "B", "G", "R"), "Y": ("Y",)}
PNG_TYPES = {"gray": 0, "RGB": 2, "RGBA": 6}
