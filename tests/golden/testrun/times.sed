s/time="[0-9.]*"/time="T"/g
