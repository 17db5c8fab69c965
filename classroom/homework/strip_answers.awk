# make homework: a notes page as a student gets it, its "Answers (for the instructor)" sections
# left out up to the next heading (make homework ANSWERS=1: kept, keep=1).
/^### Answers? \(for the instructor\)/ && !keep { skip = 1; print "*(The answers are in the teacher's copy of the notes.)*"; print ""; next }
skip && /^(#|##|###) / { skip = 0 }
!skip
