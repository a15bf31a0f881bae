# BVH seeds written at configure time into <build>/fuzz-seeds/bvh, beside the checked-in corpus/bvh: the
# variants of corpus/bvh/two_joints.bvh that each change its knee's CHANNELS line (a channel repeated, an
# unknown one, a count far past the names given, too few), and a clip with CRLF line ends, tabs and a
# joint whose channels mix positions and rotations. Generated from the one clip rather than kept as copies.
set(prep_fuzz_seed_dir ${CMAKE_BINARY_DIR}/fuzz-seeds)
file(READ ${CMAKE_CURRENT_LIST_DIR}/corpus/bvh/two_joints.bvh two_joints)
set(knee_channels "CHANNELS 3 Xrotation Yrotation Zrotation")
string(FIND "${two_joints}" "${knee_channels}" at)
if(at LESS 0)
  message(FATAL_ERROR "tests/fuzz/corpus/bvh/two_joints.bvh: the knee's line '${knee_channels}' is gone; the BVH seed variants are made by replacing it")
endif()
foreach(variant "channel_repeated|CHANNELS 3 Xrotation Xrotation Zrotation"
                "channel_unknown|CHANNELS 3 Xrotation Yrotation Wrotation"
                "channels_huge|CHANNELS 999999999 Xrotation Yrotation Zrotation"
                "channels_two|CHANNELS 2 Xrotation Yrotation")
  string(REPLACE "|" ";" parts "${variant}")
  list(GET parts 0 name)
  list(GET parts 1 line)
  string(REPLACE "${knee_channels}" "${line}" text "${two_joints}")
  file(WRITE ${prep_fuzz_seed_dir}/bvh/${name}.bvh "${text}")
endforeach()
file(WRITE ${prep_fuzz_seed_dir}/bvh/crlf_tabs_mixed_channels.bvh
  "HIERARCHY\r\nROOT Hips\r\n{\r\n\tOFFSET 0 1 0\r\n\tCHANNELS 3 Zrotation Yrotation Xrotation\r\n\tJOINT Chest\r\n"
  "\t{\r\n\t\tOFFSET 0 0.2 0\r\n\t\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\r\n"
  "\t\tEnd Site\r\n\t\t{\r\n\t\t\tOFFSET 0 0.3 0\r\n\t\t}\r\n\t}\r\n}\r\nMOTION\r\nFrames: 2\r\n"
  "Frame Time: 0.0333333\r\n0 0 0 0 0.2 0 0 0 0\r\n\t1 2 3 0 0.2 0 4 5 6\r\n")
