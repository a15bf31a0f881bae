# BVH seeds written at configure time into <build>/fuzz-seeds/bvh, beside the checked-in corpus/bvh:
# - variants of corpus/bvh/two_joints.bvh that each change one thing: its knee's CHANNELS line (a channel
#   repeated, an unknown one, a count far past the names given, too few), the knee named as the root, the
#   frame time (not a number, negative, zero), a frame's values (one too many, too few, nan and inf), no
#   MOTION section;
# - a chain of 120 joints, one inside the other (the parser's nesting);
# - a clip with CRLF line ends, tabs and a joint whose channels mix positions and rotations.
# Generated from the one clip rather than kept as copies. (offset_overflow.bvh and frame_time_tiny.bvh stay
# checked in: bvh_test.cpp reads them as the fuzzer found them.)
set(prep_fuzz_seed_dir ${CMAKE_BINARY_DIR}/fuzz-seeds)
file(READ ${CMAKE_CURRENT_LIST_DIR}/corpus/bvh/two_joints.bvh two_joints)
set(knee_channels "CHANNELS 3 Xrotation Yrotation Zrotation")
# name|the line of two_joints.bvh replaced|what replaces it (each line occurs once in it)
foreach(variant "channel_repeated|${knee_channels}|CHANNELS 3 Xrotation Xrotation Zrotation"
                "channel_unknown|${knee_channels}|CHANNELS 3 Xrotation Yrotation Wrotation"
                "channels_huge|${knee_channels}|CHANNELS 999999999 Xrotation Yrotation Zrotation"
                "channels_two|${knee_channels}|CHANNELS 2 Xrotation Yrotation"
                "duplicate_names|JOINT knee|JOINT hip"
                "frame_time_nan|Frame Time: 0.008333|Frame Time: nan"
                "frame_time_negative|Frame Time: 0.008333|Frame Time: -0.01"
                "frame_time_zero|Frame Time: 0.008333|Frame Time: 0"
                "values_extra|3 90.5 -4 20 -11 6 90 0 -20|3 90.5 -4 20 -11 6 90 0 -20 7"
                "values_missing|3 90.5 -4 20 -11 6 90 0 -20|3 90.5 -4 20 -11 6 90"
                "values_nan_inf|1.5e0 90.25 -2 10 -5.5 3 45 0 -1E1|1.5e0 nan -2 inf -5.5 3 45 0 -1E1")
  string(REPLACE "|" ";" parts "${variant}")
  list(GET parts 0 name)
  list(GET parts 1 from)
  list(GET parts 2 to)
  string(FIND "${two_joints}" "${from}" at)
  if(at LESS 0)
    message(FATAL_ERROR "tests/fuzz/corpus/bvh/two_joints.bvh: no line '${from}' to make ${name}.bvh from")
  endif()
  string(REPLACE "${from}" "${to}" text "${two_joints}")
  file(WRITE ${prep_fuzz_seed_dir}/bvh/${name}.bvh "${text}")
endforeach()
string(FIND "${two_joints}" "MOTION" at)
string(SUBSTRING "${two_joints}" 0 ${at} text)
file(WRITE ${prep_fuzz_seed_dir}/bvh/no_motion.bvh "${text}")

set(text "HIERARCHY\nROOT j0\n{\nOFFSET 0 1 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n")
set(closing "}\n")
set(values "0 0 0 0 0 0")
foreach(j RANGE 1 119)
  string(APPEND text "JOINT j${j}\n{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n")
  string(APPEND closing "}\n")
  string(APPEND values " 0 0 0")
endforeach()
string(APPEND text "End Site\n{\nOFFSET 0 1 0\n}\n" "${closing}" "MOTION\nFrames: 1\nFrame Time: 0.0333333\n" "${values}\n")
file(WRITE ${prep_fuzz_seed_dir}/bvh/deep_hierarchy.bvh "${text}")
file(WRITE ${prep_fuzz_seed_dir}/bvh/crlf_tabs_mixed_channels.bvh
  "HIERARCHY\r\nROOT Hips\r\n{\r\n\tOFFSET 0 1 0\r\n\tCHANNELS 3 Zrotation Yrotation Xrotation\r\n\tJOINT Chest\r\n"
  "\t{\r\n\t\tOFFSET 0 0.2 0\r\n\t\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\r\n"
  "\t\tEnd Site\r\n\t\t{\r\n\t\t\tOFFSET 0 0.3 0\r\n\t\t}\r\n\t}\r\n}\r\nMOTION\r\nFrames: 2\r\n"
  "Frame Time: 0.0333333\r\n0 0 0 0 0.2 0 0 0 0\r\n\t1 2 3 0 0.2 0 4 5 6\r\n")
