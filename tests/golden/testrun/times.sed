s/time="[0-9.]*"/time="T"/g
s/timestamp="[0-9T:-]*"/timestamp="T"/g
